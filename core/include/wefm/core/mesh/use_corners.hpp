#pragma once
// The corners of each use in ascending order (a counting sort of Topology::corner_use). Per-use sums
// gather over it instead of scattering from corners: each use's sum is then one thread's work, added
// in corner order, so it is the same whatever the thread count.
#include <vector>

#include "wefm/core/mesh/topology.hpp"

namespace wefm {

struct UseCorners {
  std::vector<Index> start;   // use u's corners are corner[start[u] .. start[u + 1])
  std::vector<Index> corner;  // ascending within each use
};

UseCorners use_corners(const Topology& topo);

}  // namespace wefm
