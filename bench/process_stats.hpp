#pragma once
// What the benchmark reads about its own process and machine: peak resident memory, and a
// description of the hardware and libraries so a table can be compared with another machine's.
#include <string>

namespace wefm_bench {

// VmHWM of this process in MB (0 if /proc is unavailable).
double peak_rss_mb();
// Current VmRSS in MB.
double current_rss_mb();

// Monotonic wall clock in seconds.
double now_seconds();
// CPU time of this process (all threads) in seconds: on a shared, loaded machine it says what a
// step costs when the wall clock also counts other people's work.
double cpu_seconds();

// CPU model, core count, memory, kernel, compiler and the BLAS/CHOLMOD libraries mapped into this
// process (read from /proc/self/maps, so it names what actually runs, not what was configured).
std::string machine_description();
// 1-minute load average: a benchmark taken while something else runs is noisy, and this says so.
double load_average();

}  // namespace wefm_bench
