#pragma once
// The tool's exit codes. They are part of its interface (scripts branch on them), so they are listed
// once here and printed by --help and documented in apps/README.md.
#include "wefm/wefm.h"

namespace wefm_cli {

enum ExitCode : int {
  kExitOk = 0,
  kExitUsage = 2,        // bad command line or option value
  kExitIo = 3,           // unreadable input, unwritable output, unsupported format
  kExitInvalid = 4,      // the mesh or the topology is not acceptable
  kExitSolver = 5,       // the solve failed or did not converge
  kExitCancelled = 6,    // Ctrl-C or SIGTERM
  kExitTimeLimit = 7     // --time-limit reached (also a CAD import that did not end in time)
};

// Which exit code a library status means when it comes out of reading or solving. Callers override it
// where the context says more (an out-of-range edge from --edge-mode-of is a usage error).
int exit_code_for(wefm_status status);

// The codes of a stop request (stop.hpp), not of a failure.
inline bool is_stop_code(int code) { return code == kExitCancelled || code == kExitTimeLimit; }

const char* exit_codes_help();

}  // namespace wefm_cli
