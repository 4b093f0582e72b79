#include "huge_page_malloc.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#if defined(__linux__) && defined(__GLIBC__)
#include <gnu/libc-version.h>
#include <unistd.h>
#endif

// Why: on a virtual machine every first touch of a 4 KB page is a costly fault, and a large solve
// touches most of its memory for the first time. The library advises its own large arrays (wefm.h,
// "Memory"), but what it cannot reach (Eigen's sparse value arrays, which their constructors touch
// before any advice, and the many blocks under 4 MB) still faults page by page; glibc's tunable
// puts those in huge pages too (docs/PERFORMANCE.md, "Huge-page malloc for the whole tool").
// The tunable is read once at start-up, so it can only be set by starting again. A host program
// embedding the library can set it in its own environment the same way.
//
// When not: WEFM_HUGE_PAGES=0; GLIBC_TUNABLES already names glibc.malloc.hugetlb (also the mark of
// the started-again process); LD_PRELOAD set (valgrind, sanitizers and profilers preload, and
// must keep the process they watch); transparent huge pages not in `madvise` mode (`always` needs
// no advice, `never` ignores it); glibc older than 2.35 (no such tunable); less than 2 GB of free
// memory (a machine whose memory is full of page cache can stall in compaction to find huge pages);
// `flatten` or `mesh` of a small face (every file it reads under kSmallInput): starting again
// costs a second process start, more than such a face saves in page faults.

namespace wefm_cli {

namespace {

#if defined(__linux__) && defined(__GLIBC__)
bool solving_command(const char* c) {
  for (const char* s : {"flatten", "mesh", "model", "mesh-model", "batch"})
    if (std::strcmp(c, s) == 0) return true;
  return false;
}

// About 5k triangles as OBJ (10k as binary STL): below that, the second process start costs about
// what huge-page malloc saves (docs/PERFORMANCE.md, "Measurements behind design choices").
constexpr std::uintmax_t kSmallInput = 256u << 10;

bool small_face_command(int argc, char** argv) {
  if (std::strcmp(argv[1], "flatten") != 0 && std::strcmp(argv[1], "mesh") != 0) return false;
  std::uintmax_t largest = 0;
  for (int i = 2; i < argc; ++i) {
    // Files the command writes do not count (an earlier run's output is no measure of this face).
    bool writes = false;
    for (const char* o : {"-o", "--output", "--report", "--write-topology", "--svg", "--domain-obj"}) writes = writes || std::strcmp(argv[i], o) == 0;
    if (writes) {
      ++i;
      continue;
    }
    std::error_code ec;
    if (!std::filesystem::is_regular_file(argv[i], ec)) continue;
    const std::uintmax_t size = std::filesystem::file_size(argv[i], ec);
    if (!ec) largest = std::max(largest, size);
  }
  return largest < kSmallInput;
}

bool glibc_has_tunable() {
  int major = 0, minor = 0;
  std::istringstream in(gnu_get_libc_version());
  char dot = 0;
  in >> major >> dot >> minor;
  return major > 2 || (major == 2 && minor >= 35);
}

bool thp_in_madvise_mode() {
  std::ifstream f("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string line;
  return std::getline(f, line) && line.find("[madvise]") != std::string::npos;
}

long long mem_free_kb() {
  std::ifstream f("/proc/meminfo");
  std::string key;
  long long kb = 0;
  while (f >> key >> kb) {
    if (key == "MemFree:") return kb;
    f.ignore(256, '\n');
  }
  return 0;
}
#endif

}  // namespace

void reexec_with_huge_page_malloc(int argc, char** argv) {
#if defined(__linux__) && defined(__GLIBC__)
  if (argc < 2 || !solving_command(argv[1]) || small_face_command(argc, argv)) return;
  const char* off = std::getenv("WEFM_HUGE_PAGES");
  if (off && std::strcmp(off, "0") == 0) return;
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  if (tunables && std::strstr(tunables, "glibc.malloc.hugetlb")) return;
  const char* preload = std::getenv("LD_PRELOAD");
  if (preload && *preload) return;
  if (!glibc_has_tunable() || !thp_in_madvise_mode() || mem_free_kb() < 2LL * 1024 * 1024) return;
  const std::string before = tunables ? tunables : "";
  if (!add_huge_page_malloc_tunable()) return;
  // OpenBLAS reads OPENBLAS_NUM_THREADS while it loads: at 1 it starts no pool, whose threads
  // otherwise spin for a CPU at every start (about 14 ms of a small model's 140 ms on 2 CPUs). The
  // tool sets 1 for every solve when the variable is unset (process_policy.cpp), so the started-again
  // process computes the same bits.
  const char* blas = std::getenv("OPENBLAS_NUM_THREADS");
  const bool had_blas = blas != nullptr, set_blas = !(blas && *blas);
  if (set_blas) setenv("OPENBLAS_NUM_THREADS", "1", 1);
  execv("/proc/self/exe", argv);
  // exec failed (no /proc, say): go on in this process, without the tunable.
  if (tunables) setenv("GLIBC_TUNABLES", before.c_str(), 1);
  else unsetenv("GLIBC_TUNABLES");
  if (set_blas && had_blas) setenv("OPENBLAS_NUM_THREADS", "", 1);
  else if (set_blas) unsetenv("OPENBLAS_NUM_THREADS");
#else
  (void)argc;
  (void)argv;
#endif
}

bool add_huge_page_malloc_tunable() {
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  if (tunables && std::strstr(tunables, "glibc.malloc.hugetlb")) return false;
  const std::string value = (tunables && *tunables ? std::string(tunables) + ":" : std::string()) + "glibc.malloc.hugetlb=1";
  return setenv("GLIBC_TUNABLES", value.c_str(), 1) == 0;
}

bool huge_page_malloc_active() {
  const char* t = std::getenv("GLIBC_TUNABLES");
  return t && std::strstr(t, "glibc.malloc.hugetlb=1") != nullptr;
}

}  // namespace wefm_cli
