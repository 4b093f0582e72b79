// Huge-page advice for the solve's large arrays (huge_pages.hpp): advised blocks are eligible for
// transparent huge pages where the kernel offers them, the advising allocators return ordinary
// malloc memory, and SuiteSparse allocates through them once a CHOLMOD factor exists.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>

#include <doctest/doctest.h>

#include "wefm/core/sys/huge_pages.hpp"
#include "wefm/core/linalg/sparse_cholesky.hpp"
#ifdef WEFM_HAVE_CHOLMOD
#include <SuiteSparse_config.h>
#endif

using namespace wefm;

namespace {

// Whether the kernel gives huge pages to advised memory: THP `always` or `madvise`.
bool thp_offered() {
  std::ifstream f("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string mode;
  std::getline(f, mode);
  return mode.find("[always]") != std::string::npos || mode.find("[madvise]") != std::string::npos;
}

std::uint64_t free_kb() {
  std::ifstream f("/proc/meminfo");
  std::string line;
  unsigned long long kb = 0;
  while (std::getline(f, line))
    if (std::sscanf(line.c_str(), "MemFree: %llu kB", &kb) == 1) return kb;
  return 0;
}

// The THPeligible line of the mapping that holds address a in /proc/self/smaps (-1: not found).
int thp_eligible(const void* a) {
  std::ifstream f("/proc/self/smaps");
  const auto x = reinterpret_cast<std::uintptr_t>(a);
  std::string line;
  bool inside = false;
  while (std::getline(f, line)) {
    unsigned long lo = 0, hi = 0;
    if (std::sscanf(line.c_str(), "%lx-%lx ", &lo, &hi) == 2 && line.find(':') > line.find(' ')) {
      inside = x >= lo && x < hi;
      continue;
    }
    int v = 0;
    if (inside && std::sscanf(line.c_str(), "THPeligible: %d", &v) == 1) return v;
  }
  return -1;
}

}  // namespace

TEST_CASE("an advised large block is eligible for transparent huge pages") {
  const std::size_t bytes = std::size_t{64} << 20;  // above glibc's largest mmap threshold: a fresh mapping
  char* p = static_cast<char*>(huge_malloc(bytes));
  REQUIRE(p != nullptr);
  for (std::size_t i = 0; i < bytes; i += 4096) p[i] = 1;
  // 2 MB into the block is inside its aligned interior, whatever the block's start.
  const int eligible = thp_eligible(p + (std::size_t{4} << 20));
  if (!huge_pages_enabled() || !thp_offered() || free_kb() < (std::uint64_t{1} << 20) || eligible < 0) {
    MESSAGE("huge pages not offered here (WEFM_HUGE_PAGES=0, THP off, little free memory, or no THPeligible in smaps): not checked");
  } else {
    CHECK(eligible == 1);
  }
  std::free(p);
}

TEST_CASE("a small block is not advised, and huge_calloc memory is zero") {
  char* small = static_cast<char*>(huge_malloc(1 << 20));
  REQUIRE(small != nullptr);
  std::memset(small, 7, 1 << 20);
  std::free(small);
  const std::size_t n = std::size_t{40} << 20;
  auto* z = static_cast<unsigned char*>(huge_calloc(n, 1));
  REQUIRE(z != nullptr);
  bool zero = true;
  for (std::size_t i = 0; i < n; i += 997) zero = zero && z[i] == 0;
  CHECK(zero);
  std::free(z);
}

#ifdef WEFM_HAVE_CHOLMOD
TEST_CASE("SuiteSparse allocates through the advising allocator once a CHOLMOD factor exists") {
  SparseCholesky chol(Backend::Cholmod);
  if (!huge_pages_enabled()) {
    const bool libc = SuiteSparse_config.malloc_func == &std::malloc;
    CHECK(libc);
    return;
  }
  const bool advising_malloc = SuiteSparse_config.malloc_func == &huge_malloc;
  const bool advising_calloc = SuiteSparse_config.calloc_func == &huge_calloc;
  CHECK(advising_malloc);
  CHECK(advising_calloc);
  // Blocks from either allocator are ordinary malloc blocks: CHOLMOD frees them with free().
  void* p = SuiteSparse_config.malloc_func(std::size_t{8} << 20);
  REQUIRE(p != nullptr);
  SuiteSparse_config.free_func(p);
}
#endif
