#pragma once
// Work that cannot be interrupted (Open CASCADE's import) run where it can be abandoned: a forked
// child process computes bytes and writes them to a pipe; the parent reads them while polling the
// stop requests (stop.hpp) and its own time limit, and kills the child when either comes first.
// The child also dies with the parent (PR_SET_DEATHSIG) and is killed by the second-signal handler.
// Call it while the process has no other threads of its own: the child runs `work` after fork().
#include <functional>
#include <string>

namespace wefm_cli {

struct ChildOutcome {
  enum Kind { kDone, kStopped, kTimedOut, kFailed } kind = kFailed;
  std::string bytes;    // kDone: everything the child wrote
  std::string problem;  // kFailed: what happened to the child ("was killed by signal 11 (Segmentation fault)")
};

// `seconds` > 0 bounds the child's run (besides the stop requests). `memory_mb` > 0 caps the child's
// address space (RLIMIT_AS, in the child only): a runaway allocation fails there, reported as
// kFailed "ran out of memory", instead of pushing the machine into swap or the OOM killer. (No cap
// in AddressSanitizer builds: the sanitizer's shadow reservation alone exceeds any.)
ChildOutcome run_in_child(const std::function<std::string()>& work, double seconds, double memory_mb = 0);

// The machine's physical memory in MB (0 when unknown): the import child's default cap.
double physical_memory_mb();

}  // namespace wefm_cli
