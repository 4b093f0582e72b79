#pragma once
// Stop requests: SIGINT, SIGTERM and the --time-limit deadline, for every command and every stage.
//
// main() installs the handlers once. The first signal only sets a flag that the stages poll
// (between stages, in the progress callback, in the cancel watcher that calls wefm_face_cancel, in
// every output write, in the wait for the CAD import child), so the command stops cleanly with exit
// code 6. A second signal ends the process at once: the handler removes the temporary files that
// outputs are being written to (output_file.hpp), kills the CAD import child and dies by the signal,
// so even then no partial output is left. A passed deadline is a stop request with exit code 7.
#include <string>
#include <sys/types.h>

namespace wefm_cli {

// hold_stop_signals blocks SIGINT and SIGTERM; install_stop_handlers installs the handler and
// unblocks them (a signal that came in between is then handled).
void hold_stop_signals();
void install_stop_handlers();

// True once a stop was requested: a signal, or the deadline has passed (checked on each call).
bool interrupted();
// The exit code of the stop: kExitTimeLimit after the deadline (and no signal), else kExitCancelled
// (also for a library cancel that no stop request caused). And a phrase saying why.
int stop_exit_code();
std::string stop_reason();
// The command's exit code as it ends: unchanged when no stop was requested; else the stop's, and
// "wefm: WHAT: REASON" on stderr. A stop heard between faces, or while the summary is written,
// leaves no face to report it, and an exit of 6 or 7 must still say why.
int exit_after_stop(int exit_code, const std::string& what);

// --time-limit: the whole command must end within `seconds` from now (> 0).
void set_time_limit(double seconds);
// Seconds left before the deadline, or a negative number when there is none.
double seconds_left();

// Open CASCADE cannot be interrupted, so the CAD import runs in a child process that is killed at
// the deadline; without --time-limit it still gets this long (a mutated STEP file can make OCCT
// spin for hours).
constexpr double kDefaultImportSeconds = 600;

// Paths that the second-signal handler removes (temporaries being written). register returns a slot
// (-1 when all are taken: the file is then only removed by its owner) and copies the path.
int register_temporary(const std::string& path);
void unregister_temporary(int slot);

// The CAD import child that the second-signal handler kills (0 = none).
void set_child_process(pid_t pid);

}  // namespace wefm_cli
