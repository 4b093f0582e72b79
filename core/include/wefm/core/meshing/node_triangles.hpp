#pragma once
// The triangles around each node of a triangle list, in one array (a counting sort by node: no
// per-node vectors, no hashing).
#include <array>
#include <vector>

#include "wefm/core/sys/types.hpp"

namespace wefm::meshing {

// The triangles of node v are items[start[v] .. start[v + 1]), in increasing triangle order.
struct NodeTriangles {
  std::vector<Index> start, items;
};

inline NodeTriangles node_triangles(size_t nodes, const std::vector<std::array<Index, 3>>& tris) {
  NodeTriangles r{std::vector<Index>(nodes + 1, 0), std::vector<Index>(3 * tris.size())};
  for (const auto& t : tris)
    for (Index v : t) r.start[static_cast<size_t>(v) + 1]++;
  for (size_t k = 1; k <= nodes; ++k) r.start[k] += r.start[k - 1];
  std::vector<Index> fill(r.start.begin(), r.start.end() - 1);
  for (Index t = 0; t < static_cast<Index>(tris.size()); ++t)
    for (Index v : tris[static_cast<size_t>(t)]) r.items[static_cast<size_t>(fill[static_cast<size_t>(v)]++)] = t;
  return r;
}

}  // namespace wefm::meshing
