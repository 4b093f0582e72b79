// Huge-page advice for the solve's large arrays (huge_pages.hpp): off until asked for; advised
// blocks are eligible for transparent huge pages where the kernel offers them, the advising
// allocators return ordinary malloc memory, and SuiteSparse allocates through them while the
// advice is on, and through the C library's allocator again after.
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

std::string thp_mode() {
  std::ifstream f("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string mode;
  std::getline(f, mode);
  return mode;
}

// Whether the kernel gives huge pages to advised memory: THP `always` or `madvise`.
bool thp_offered() {
  const std::string mode = thp_mode();
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

// THPeligible of a fresh 64 MB huge_malloc block, touched (-1: not found in smaps).
int fresh_block_eligible() {
  const std::size_t bytes = std::size_t{64} << 20;  // above glibc's largest mmap threshold: a fresh mapping
  char* p = static_cast<char*>(huge_malloc(bytes));
  REQUIRE(p != nullptr);
  for (std::size_t i = 0; i < bytes; i += 4096) p[i] = 1;
  // 2 MB into the block is inside its aligned interior, whatever the block's start.
  const int eligible = thp_eligible(p + (std::size_t{4} << 20));
  std::free(p);
  return eligible;
}

}  // namespace

TEST_CASE("an advised large block is eligible for transparent huge pages") {
  set_huge_pages(true);
  CHECK(huge_pages_enabled());
  const int eligible = fresh_block_eligible();
  set_huge_pages(false);
  if (!thp_offered() || free_kb() < (std::uint64_t{1} << 20) || eligible < 0) {
    MESSAGE("huge pages not offered here (THP off, little free memory, or no THPeligible in smaps): not checked");
  } else {
    CHECK(eligible == 1);
  }
}

TEST_CASE("no advice unless asked for") {
  CHECK_FALSE(huge_pages_enabled());  // the process default
  const int eligible = fresh_block_eligible();
  // Under THP `always` every block is eligible, advised or not: only `madvise` mode tells.
  if (thp_mode().find("[madvise]") == std::string::npos || eligible < 0) {
    MESSAGE("THP not in madvise mode or no THPeligible in smaps: not checked");
  } else {
    CHECK(eligible == 0);
  }
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
TEST_CASE("SuiteSparse allocates through the advising allocator only while the advice is on") {
  // doctest cannot print function pointers: each comparison is made a bool first.
  const auto libc = [] { return SuiteSparse_config.malloc_func == &std::malloc && SuiteSparse_config.calloc_func == &std::calloc; };
  SparseCholesky chol(Backend::Cholmod);
  const bool untouched = libc();  // a CHOLMOD factor alone changes nothing
  CHECK(untouched);
  set_huge_pages(true);
  const bool advising = SuiteSparse_config.malloc_func == &huge_malloc && SuiteSparse_config.calloc_func == &huge_calloc;
  CHECK(advising);
  // Blocks from either allocator are ordinary malloc blocks: CHOLMOD frees them with free().
  void* p = SuiteSparse_config.malloc_func(std::size_t{8} << 20);
  REQUIRE(p != nullptr);
  set_huge_pages(false);
  SuiteSparse_config.free_func(p);
  const bool restored = libc();
  CHECK(restored);
}

TEST_CASE("a host's own SuiteSparse allocator is kept when the advice goes on and off") {
  struct Host {
    static void* alloc(std::size_t n) { return std::malloc(n); }
    static void* alloc0(std::size_t n, std::size_t m) { return std::calloc(n, m); }
  };
  void* (*const saved_malloc)(std::size_t) = SuiteSparse_config.malloc_func;
  void* (*const saved_calloc)(std::size_t, std::size_t) = SuiteSparse_config.calloc_func;
  SuiteSparse_config.malloc_func = &Host::alloc;
  SuiteSparse_config.calloc_func = &Host::alloc0;
  set_huge_pages(true);
  const bool kept_on = SuiteSparse_config.malloc_func == &Host::alloc && SuiteSparse_config.calloc_func == &Host::alloc0;
  set_huge_pages(false);
  const bool kept_off = SuiteSparse_config.malloc_func == &Host::alloc && SuiteSparse_config.calloc_func == &Host::alloc0;
  SuiteSparse_config.malloc_func = saved_malloc;
  SuiteSparse_config.calloc_func = saved_calloc;
  CHECK(kept_on);
  CHECK(kept_off);
}
#endif
