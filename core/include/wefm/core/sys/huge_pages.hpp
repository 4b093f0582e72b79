#pragma once
// Transparent huge pages for the solve's large arrays. A large solve touches most of its memory for
// the first time, one page fault per 4 KB page, and on a virtual machine faults are costly enough
// to be a large share of the solve (docs/PERFORMANCE.md, "Measurements behind design choices").
// Advised blocks fault in 2 MB at a time, 512 times fewer faults. Linux honours the advice when
// /sys/kernel/mm/transparent_hugepage/enabled is `always` or `madvise` (Debian's default);
// elsewhere it is a no-op. Off unless the host asks for it (set_huge_pages, the C API's process
// policy): the advice stays on the address range after the block is freed, where the host's
// allocator hands it out again, so it is the host's choice, like SuiteSparse's allocator.
#include <cstddef>
#include <vector>

namespace wefm {

// Whether advice is given: false until set_huge_pages(true).
bool huge_pages_enabled();

// Turns the advice on or off for the process. On also routes SuiteSparse's allocations (CHOLMOD's
// factor and workspace) through huge_malloc / huge_calloc where SuiteSparse still uses the C
// library's allocator (a host that installed its own keeps it); off puts the C library's back where
// they are still ours. Blocks stay compatible with free(), so blocks allocated before or after a
// switch mix freely. SuiteSparse_config is a plain global: the caller makes sure no SuiteSparse
// call runs meanwhile.
void set_huge_pages(bool on);

// Advises the 2 MB-aligned interior of [p, p + bytes) for huge pages, for blocks of at least
// 4 MB that are not yet touched (advice on touched pages is harmless: khugepaged may merge them).
void advise_huge_pages(void* p, std::size_t bytes);

// Reserves room for n elements of an empty vector, advised before anything touches it: follow
// with resize or assign. A vector that already holds elements is left as it is.
template <class T, class A>
void reserve_huge(std::vector<T, A>& v, std::size_t n) {
  if (!v.empty() || v.capacity() >= n) return;
  v.reserve(n);
  advise_huge_pages(v.data(), n * sizeof(T));
}

// v.assign(n, value) with the room reserved and advised first (v is normally empty).
template <class T, class A>
void assign_huge(std::vector<T, A>& v, std::size_t n, const typename std::vector<T, A>::value_type& value = T()) {
  reserve_huge(v, n);
  v.assign(n, value);
}

// Advises a compressed Eigen sparse matrix's index and value arrays, between resizeNonZeros and
// the first write.
template <class Sparse>
void advise_huge_pages_sparse(Sparse& m) {
  const std::size_t nz = static_cast<std::size_t>(m.nonZeros());
  advise_huge_pages(m.valuePtr(), nz * sizeof(*m.valuePtr()));
  advise_huge_pages(m.innerIndexPtr(), nz * sizeof(*m.innerIndexPtr()));
}

// malloc / calloc that advise large blocks; the memory is freed with std::free.
void* huge_malloc(std::size_t bytes);
void* huge_calloc(std::size_t count, std::size_t size);

}  // namespace wefm
