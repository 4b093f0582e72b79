#pragma once
// Transfinite (mapped) meshing (METHOD §9.2): four corners on the outer loop, opposite sides with
// equal node counts (uniform in 3D arc length), boundary-blended (Coons) interpolation in UV.
#include "wefm/core/meshing/domain_mesh.hpp"
#include "wefm/core/meshing/surface_map.hpp"

namespace wefm::meshing {

// Loop positions of the four corners on the outer loop: the caller's uses, or the four largest
// left turns in UV. Throws Error(unsupported) when the face has holes or fewer than four vertices.
std::array<size_t, 4> transfinite_corners(const Topology& topo, const VectorXc& uv, const std::array<Index, 4>& given);

void transfinite_mesh(const TriMesh& mesh, const Topology& topo, const VectorXc& uv, const SurfaceMap& map, const MeshOptions& options,
                      DomainMesh& out);

}  // namespace wefm::meshing
