#pragma once
// Loops split over std::threads so that the result never depends on the thread count: callers
// write each output element from exactly one range with the same arithmetic whatever the split,
// and keep every sum in a fixed order (per-use sums gather over the use's corners, K's columns over
// their rows, pattern blocks of a fixed size). Threads only decide which range runs where.
#include <functional>

#include "wefm/core/sys/types.hpp"

namespace wefm {

// Runs body(begin, end) over [0, n) on at most `threads` threads, each with at least `grain`
// elements (threads <= 1 or a small n: inline, in the caller's thread). Ranges are contiguous; body
// must write only elements of its own range or thread-private data. An exception in any range is
// rethrown here after every thread has joined.
void parallel_for(int threads, Index n, const std::function<void(Index, Index)>& body, Index grain = 16384);

}  // namespace wefm
