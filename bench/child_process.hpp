#pragma once
// Runs a program as a child process with a time limit and reports what the kernel measured for
// it (wall time, peak resident memory, CPU time). Each benchmark case is one child so its peak
// memory is its own, and a case that runs away is killed instead of stalling the whole run.
#include <string>
#include <vector>

namespace wefm_bench {

struct ChildResult {
  bool started = false;
  bool timed_out = false;
  int exit_code = -1;      // -1 when killed by a signal
  int signal = 0;
  std::string out;         // everything the child wrote to stdout
  double wall = 0;         // seconds
  double user = 0, sys = 0;
  double max_rss_mb = 0;   // ru_maxrss of the child
};

// argv[0] is the program path. stderr is inherited (so progress and errors stay visible).
ChildResult run_child(const std::vector<std::string>& argv, double timeout_seconds);

// Directory holding the running executable (from /proc/self/exe), with a trailing slash.
std::string executable_dir();

}  // namespace wefm_bench
