#pragma once
// Free triangular meshing of the domain (METHOD §9.2): constrained Delaunay triangulation of the
// boundary nodes, frontal-Delaunay node placement at the 3D size field (frontal.hpp), circumcentre
// refinement for what the front leaves, then improvement in 3D (smoothing.hpp).
#include "wefm/core/meshing/domain_mesh.hpp"
#include "wefm/core/meshing/surface_map.hpp"

namespace wefm::meshing {

// `expected_elements`: about how many triangles the face's area asks for at options.size; refinement
// stops at ten times that (plus room for the boundary's grading) whatever else asks for more.
void free_mesh(const std::vector<LoopNodes>& loops, const SurfaceMap& map, const MeshOptions& options, double expected_elements,
               DomainMesh& out, const MeshControl& control = {});

}  // namespace wefm::meshing
