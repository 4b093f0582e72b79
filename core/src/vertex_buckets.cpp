#include "wefm/core/vertex_buckets.hpp"

#include <algorithm>

namespace wefm {

namespace {

// Counting sort of items by a key in [0, buckets), stable in item order, then each bucket sorted
// by `less`. Buckets hold the few items of one vertex; a huge fan still sorts in n log n.
template <class T, class Key, class Less>
std::vector<T> bucket_sort(std::vector<T> items, Index buckets, Key key, Less less) {
  std::vector<Index> start(static_cast<size_t>(buckets) + 1, 0);
  for (const T& x : items) ++start[static_cast<size_t>(key(x)) + 1];
  for (size_t b = 1; b < start.size(); ++b) start[b] += start[b - 1];
  std::vector<T> out(items.size());
  std::vector<Index> fill(start.begin(), start.end() - 1);
  for (const T& x : items) out[static_cast<size_t>(fill[static_cast<size_t>(key(x))]++)] = x;
  for (size_t b = 0; b + 1 < start.size(); ++b) {
    const auto first = out.begin() + start[b], last = out.begin() + start[b + 1];
    if (last - first < 2) continue;
    if (last - first <= 16) {  // insertion sort: the common case of a handful of items
      for (auto i = first + 1; i != last; ++i)
        for (auto j = i; j != first && less(*j, *(j - 1)); --j) std::iter_swap(j, j - 1);
    } else {
      std::sort(first, last, less);
    }
  }
  return out;
}

}  // namespace

std::vector<EdgeKey> half_edges_by_edge(const std::vector<Tri>& triangles, Index vertex_count) {
  std::vector<EdgeKey> keys(triangles.size() * 3);
  for (size_t t = 0; t < triangles.size(); ++t)
    for (int j = 0; j < 3; ++j) {
      const Index a = triangles[t][static_cast<size_t>(j)], b = triangles[t][static_cast<size_t>((j + 1) % 3)];
      keys[3 * t + static_cast<size_t>(j)] = {std::min(a, b), std::max(a, b), static_cast<Index>(3 * t + static_cast<size_t>(j))};
    }
  return bucket_sort(
      std::move(keys), vertex_count, [](const EdgeKey& k) { return k.lo; },
      [](const EdgeKey& x, const EdgeKey& y) { return x.hi < y.hi || (x.hi == y.hi && x.h < y.h); });
}

std::vector<Index> triangles_by_vertex_set(const std::vector<Tri>& triangles, Index vertex_count, std::vector<Tri>& canon) {
  canon = triangles;
  for (Tri& f : canon) std::sort(f.begin(), f.end());
  std::vector<Index> order(triangles.size());
  for (size_t t = 0; t < order.size(); ++t) order[t] = static_cast<Index>(t);
  return bucket_sort(
      std::move(order), vertex_count, [&](Index t) { return canon[static_cast<size_t>(t)][0]; },
      [&](Index a, Index b) {
        const Tri &x = canon[static_cast<size_t>(a)], &y = canon[static_cast<size_t>(b)];
        return x[1] < y[1] || (x[1] == y[1] && (x[2] < y[2] || (x[2] == y[2] && a < b)));
      });
}

}  // namespace wefm
