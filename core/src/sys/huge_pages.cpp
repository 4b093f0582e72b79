#include "wefm/core/sys/huge_pages.hpp"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <atomic>
#include <sys/mman.h>

#ifdef WEFM_HAVE_CHOLMOD
#include <SuiteSparse_config.h>
#endif

namespace wefm {

namespace {
constexpr std::size_t kHugePage = std::size_t{2} << 20;
constexpr std::size_t kMinBlock = std::size_t{4} << 20;
std::atomic<bool> g_huge_pages{false};

// Free memory in bytes (MemFree, not MemAvailable: page cache is not free for a huge page), or 0
// when unknown.
std::size_t free_memory() {
  std::FILE* f = std::fopen("/proc/meminfo", "r");
  if (!f) return 0;
  char line[128];
  unsigned long long kb = 0;
  while (std::fgets(line, sizeof line, f))
    if (std::sscanf(line, "MemFree: %llu kB", &kb) == 1) break;
  std::fclose(f);
  return static_cast<std::size_t>(kb) * 1024;
}
}  // namespace

bool huge_pages_enabled() { return g_huge_pages.load(std::memory_order_relaxed); }

void advise_huge_pages(void* p, std::size_t bytes) {
#ifdef MADV_HUGEPAGE
  if (!p || bytes < kMinBlock || !huge_pages_enabled()) return;
  // With memory full of page cache, a huge-page fault in an advised block compacts memory on the
  // spot (transparent_hugepage/defrag `madvise`, Debian's default) and can stall for longer than
  // the 4 KB faults it saves: advise only while free memory is ample.
  if (free_memory() < 2 * bytes + (std::size_t{512} << 20)) return;
  const auto a = reinterpret_cast<std::uintptr_t>(p);
  const std::uintptr_t first = (a + kHugePage - 1) & ~(kHugePage - 1);
  const std::uintptr_t last = (a + bytes) & ~(kHugePage - 1);
  if (last > first) madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);  // advice only: failure is harmless
#else
  (void)p;
  (void)bytes;
#endif
}

// Large blocks come from glibc's mmap path, untouched until the caller writes them (calloc too:
// fresh mappings are known zero and not cleared), so the advice lands before the first fault.
void* huge_malloc(std::size_t bytes) {
  void* p = std::malloc(bytes);
  advise_huge_pages(p, bytes);
  return p;
}

void* huge_calloc(std::size_t count, std::size_t size) {
  void* p = std::calloc(count, size);
  if (p && size && count <= SIZE_MAX / size) advise_huge_pages(p, count * size);
  return p;
}

#ifdef WEFM_HAVE_CHOLMOD
namespace {
// The C library's allocator back in SuiteSparse where the pointers are still ours.
void restore_libc_allocator() {
  if (SuiteSparse_config.malloc_func == &huge_malloc) SuiteSparse_config.malloc_func = &std::malloc;
  if (SuiteSparse_config.calloc_func == &huge_calloc) SuiteSparse_config.calloc_func = &std::calloc;
}

// Puts the C library's allocator back if the library is unloaded while SuiteSparse stays loaded
// (a host that loaded both): the pointers must not outlive this code.
struct RestoreAtUnload {
  ~RestoreAtUnload() { restore_libc_allocator(); }
};
}  // namespace
#endif

void set_huge_pages(bool on) {
  g_huge_pages.store(on);
#ifdef WEFM_HAVE_CHOLMOD
  if (on) {
    static RestoreAtUnload restore;
    if (SuiteSparse_config.malloc_func == &std::malloc) SuiteSparse_config.malloc_func = &huge_malloc;
    if (SuiteSparse_config.calloc_func == &std::calloc) SuiteSparse_config.calloc_func = &huge_calloc;
  } else {
    restore_libc_allocator();
  }
#endif
}

}  // namespace wefm
