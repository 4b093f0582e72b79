#include "wefm/core/mesh/vertex_buckets.hpp"
#include "wefm/core/sys/huge_pages.hpp"

#include <algorithm>

namespace wefm {

namespace {

// Counting sort of n generated items by a key in [0, buckets), stable in item order, then each
// bucket sorted by `less`. Items are generated twice (count, then place) rather than stored twice:
// the pass is memory-bound. Buckets hold the few items of one vertex; a huge fan still sorts in
// n log n.
template <class T, class Item, class Key, class Less>
void bucket_sort(size_t n, Index buckets, Item item, Key key, Less less, std::vector<Index>& start, std::vector<T>& out) {
  start.assign(static_cast<size_t>(buckets) + 1, 0);
  for (size_t i = 0; i < n; ++i) ++start[static_cast<size_t>(key(i)) + 1];
  for (size_t b = 1; b < start.size(); ++b) start[b] += start[b - 1];
  assign_huge(out, n);
  std::vector<Index> fill(start.begin(), start.end() - 1);
  for (size_t i = 0; i < n; ++i) out[static_cast<size_t>(fill[static_cast<size_t>(key(i))]++)] = item(i);
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
}

}  // namespace

EdgeBuckets half_edges_by_edge(const std::vector<Tri>& triangles, Index vertex_count) {
  EdgeBuckets eb;
  auto ends = [&](size_t h) {
    const Tri& t = triangles[h / 3];
    return std::make_pair(t[h % 3], t[(h % 3 + 1) % 3]);
  };
  bucket_sort(
      triangles.size() * 3, vertex_count,
      [&](size_t h) { return EdgeBuckets::Entry{std::max(ends(h).first, ends(h).second), static_cast<Index>(h)}; },
      [&](size_t h) { return std::min(ends(h).first, ends(h).second); },
      [](const EdgeBuckets::Entry& x, const EdgeBuckets::Entry& y) { return x.hi < y.hi || (x.hi == y.hi && x.h < y.h); }, eb.start,
      eb.entries);
  return eb;
}

std::vector<Index> triangles_by_vertex_set(const std::vector<Tri>& triangles, Index vertex_count, std::vector<Tri>& canon) {
  canon = triangles;
  for (Tri& f : canon) std::sort(f.begin(), f.end());
  std::vector<Index> start, order;
  bucket_sort(
      triangles.size(), vertex_count, [](size_t t) { return static_cast<Index>(t); }, [&](size_t t) { return canon[t][0]; },
      [&](Index a, Index b) {
        const Tri &x = canon[static_cast<size_t>(a)], &y = canon[static_cast<size_t>(b)];
        return x[1] < y[1] || (x[1] == y[1] && (x[2] < y[2] || (x[2] == y[2] && a < b)));
      },
      start, order);
  return order;
}

}  // namespace wefm
