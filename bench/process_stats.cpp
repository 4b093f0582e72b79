#include "process_stats.hpp"

#include <sys/utsname.h>

#include <chrono>
#include <ctime>
#include <cstdio>
#include <fstream>
#include <set>
#include <thread>

namespace wefm_bench {

namespace {

double status_field_mb(const char* key) {
  std::ifstream f("/proc/self/status");
  std::string line;
  const std::string k = key;
  while (std::getline(f, line))
    if (line.compare(0, k.size(), k) == 0) return std::stod(line.substr(k.size())) / 1024.0;
  return 0.0;
}

std::string first_field(const char* path, const std::string& key) {
  std::ifstream f(path);
  std::string line;
  while (std::getline(f, line))
    if (line.compare(0, key.size(), key) == 0) {
      const auto colon = line.find(':');
      if (colon == std::string::npos) return "";
      const auto start = line.find_first_not_of(" \t", colon + 1);
      return start == std::string::npos ? "" : line.substr(start);
    }
  return "";
}

// Shared libraries whose name says which linear algebra runs (libopenblas, libblas, libcholmod...).
std::string mapped_math_libraries() {
  std::ifstream f("/proc/self/maps");
  std::string line;
  std::set<std::string> names;
  while (std::getline(f, line)) {
    const auto slash = line.rfind('/');
    if (slash == std::string::npos) continue;
    const std::string name = line.substr(slash + 1);
    for (const char* key : {"blas", "lapack", "cholmod", "metis", "gomp", "CGAL", "gmp"})
      if (name.find(key) != std::string::npos) names.insert(name);
  }
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

}  // namespace

double peak_rss_mb() { return status_field_mb("VmHWM:"); }
double current_rss_mb() { return status_field_mb("VmRSS:"); }

double now_seconds() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double load_average() {
  double l = 0;
  if (std::FILE* f = std::fopen("/proc/loadavg", "r")) {
    if (std::fscanf(f, "%lf", &l) != 1) l = 0;
    std::fclose(f);
  }
  return l;
}

std::string machine_description() {
  std::string cpu = first_field("/proc/cpuinfo", "model name");
  if (cpu.empty()) cpu = "unknown CPU";
  const std::string mem = first_field("/proc/meminfo", "MemTotal");
  utsname u{};
  std::string kernel = uname(&u) == 0 ? std::string(u.sysname) + " " + u.release : "unknown kernel";
  std::string d = cpu + ", " + std::to_string(std::thread::hardware_concurrency()) + " logical CPUs, " + mem + " RAM; " + kernel +
                  "; compiler " + __VERSION__;
  const std::string libs = mapped_math_libraries();
  if (!libs.empty()) d += "; libraries " + libs;
  return d;
}

}  // namespace wefm_bench
