#pragma once
// Transfinite (mapped) meshing (METHOD §9.2): four corners on the outer loop, opposite sides with
// equal node counts (uniform in 3D arc length), boundary-blended (Coons) interpolation in UV.
#include <optional>

#include "wefm/core/meshing/boundary.hpp"
#include "wefm/core/meshing/domain_mesh.hpp"
#include "wefm/core/meshing/surface_map.hpp"

namespace wefm::meshing {

// Loop positions of the four corners on the outer loop: the caller's uses, or the four largest
// left turns in UV. Throws Error(unsupported) when the face has holes or fewer than four vertices.
std::array<size_t, 4> transfinite_corners(const Topology& topo, const VectorXc& uv, const std::array<Index, 4>& given);

// The loop positions of a four-sided face's corners, in loop order: one loop, exactly four vertices
// where its UV boundary turns left by 30 to 150 degrees, and every other turn under 20 degrees
// either way (a side may curve, in many small turns). Empty for any other face.
std::optional<std::array<size_t, 4>> four_corners(const Topology& topo, const VectorXc& uv);

// Without `given` edge nodes the sides are uniform at the option's size (opposite sides get the
// mean count). With them the sides are the boundary the free mesher would use, the caller's nodes
// included, so the face conforms to its neighbours; opposite sides must then have as many nodes
// (else Error(unsupported)).
void transfinite_mesh(const TriMesh& mesh, const Topology& topo, const VectorXc& uv, const SurfaceMap& map, const MeshOptions& options,
                      const EdgeNodes& given, DomainMesh& out);

}  // namespace wefm::meshing
