#pragma once
// Mesh improvement judged in 3D: edge flips and UV node moves are kept only when the worst Lo
// lambda of the 3D triangles they touch improves (the UV triangles must stay positive); then a few
// passes of optimise_nodes (node_optimisation.hpp) for the sum of log lambda; last, a triangle still
// below lambda 0.3 gets a node on its longest inner edge where that lifts the worst element near it
// (a needle across a strip narrower than h has no interior node to move). Boundary nodes never move
// and are never added: faces sharing an edge keep sharing its nodes.
#include <array>
#include <vector>

#include "wefm/core/meshing/mesh_control.hpp"
#include "wefm/core/meshing/surface_map.hpp"

namespace wefm::meshing {

// Nodes below `fixed` (the boundary nodes) never move. Returns the number of accepted moves.
// `control` is checked before every pass (fractions 0.8 to 0.95): a stop throws Error(cancelled).
std::int64_t improve_in_3d(std::vector<P2>& uv, std::vector<Vec3>& xyz, std::vector<std::array<Index, 3>>& tris, Index fixed,
                           int iterations, const SurfaceMap& map, const MeshControl& control);

}  // namespace wefm::meshing
