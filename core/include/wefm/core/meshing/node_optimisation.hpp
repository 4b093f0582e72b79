#pragma once
// Node placement by optimisation on the surface: each interior node moves along the gradient of
// the sum of log Lo's lambda over the triangles around it (the quantity lambda_mesh averages),
// taken in 3D and projected on the tangent plane, then brought back to UV through the map's
// Jacobian. A parabola along the gradient picks the step. A move is kept when the sum improves,
// no UV triangle inverts and the star's worst element stays above min(its old value, `floor`).
#include <array>
#include <cstdint>
#include <vector>

#include "wefm/core/meshing/surface_map.hpp"

namespace wefm::meshing {

// Nodes below `fixed` never move. Returns the number of moves kept.
std::int64_t optimise_nodes(std::vector<P2>& uv, std::vector<Vec3>& xyz, const std::vector<std::array<Index, 3>>& tris, Index fixed,
                            const SurfaceMap& map, double floor);

}  // namespace wefm::meshing
