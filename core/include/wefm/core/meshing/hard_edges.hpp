#pragma once
// Hard edges inside a face (METHOD §9.6): mesh edges with the domain on both sides that every later
// step must keep as edges, such as the segments of a scar (a repeated edge kept closed, along which
// the boundary runs both ways). Flips and splits leave them, recombination never pairs the two
// triangles on them, and an all-quad split halves them.
#include <array>
#include <cstdint>
#include <unordered_set>
#include <utility>
#include <vector>

#include "wefm/core/sys/types.hpp"

namespace wefm::meshing {

// One key per undirected edge.
inline std::uint64_t edge_key(Index a, Index b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

class HardEdges {
 public:
  HardEdges() = default;
  explicit HardEdges(const std::vector<std::array<Index, 2>>& edges) {
    keys_.reserve(edges.size());
    for (const auto& e : edges) keys_.insert(edge_key(e[0], e[1]));
  }
  bool has(Index a, Index b) const { return !keys_.empty() && keys_.count(edge_key(a, b)) > 0; }
  bool empty() const { return keys_.empty(); }

 private:
  std::unordered_set<std::uint64_t> keys_;
};

}  // namespace wefm::meshing
