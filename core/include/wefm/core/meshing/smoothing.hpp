#pragma once
// Mesh improvement judged in 3D: edge flips and UV node moves are kept only when the worst Lo
// lambda of the 3D triangles they touch improves (the UV triangles must stay positive); then a few
// passes of optimise_nodes (node_optimisation.hpp) for the sum of log lambda.
#include <array>
#include <vector>

#include "wefm/core/meshing/surface_map.hpp"

namespace wefm::meshing {

// Nodes below `fixed` (the boundary nodes) never move. Returns the number of accepted moves.
std::int64_t improve_in_3d(std::vector<P2>& uv, std::vector<Vec3>& xyz, std::vector<std::array<Index, 3>>& tris, Index fixed,
                           int iterations, const SurfaceMap& map);

}  // namespace wefm::meshing
