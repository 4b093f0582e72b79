#pragma once
// Loops split over std::threads so that the result never depends on the thread count: the work is
// cut into fixed blocks whatever the thread count, every output element is computed by one block
// with the same arithmetic, and sums over blocks are added in block order. Threads only decide
// which block runs where.
#include <algorithm>
#include <functional>
#include <vector>

#include "wefm/core/types.hpp"

namespace wefm {

// Elements per block of parallel_sum: a constant so that the summation order, and with it the
// rounding, is the same for 1 thread or 64.
constexpr Index kSumBlock = 4096;

// Runs body(begin, end) over [0, n) on at most `threads` threads, each with at least `grain`
// elements (threads <= 1 or a small n: inline, in the caller's thread). Ranges are contiguous; body
// must write only elements of its own range or thread-private data. An exception in any range is
// rethrown here after every thread has joined.
void parallel_for(int threads, Index n, const std::function<void(Index, Index)>& body, Index grain = 16384);

// Sum over i in [0, n) of term(i): each kSumBlock-sized block summed in index order, then the block
// sums in block order. Bit-identical for every thread count.
template <class Term>
double parallel_sum(int threads, Index n, const Term& term) {
  if (n <= 0) return 0.0;
  const Index blocks = (n + kSumBlock - 1) / kSumBlock;
  std::vector<double> partial(static_cast<size_t>(blocks), 0.0);
  parallel_for(
      threads, blocks,
      [&](Index b0, Index b1) {
        for (Index b = b0; b < b1; ++b) {
          double s = 0.0;
          const Index end = std::min(n, (b + 1) * kSumBlock);
          for (Index i = b * kSumBlock; i < end; ++i) s += term(i);
          partial[static_cast<size_t>(b)] = s;
        }
      },
      4);
  double total = 0.0;
  for (double s : partial) total += s;
  return total;
}

}  // namespace wefm
