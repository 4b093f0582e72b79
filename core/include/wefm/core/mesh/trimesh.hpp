#pragma once
// The 3D triangulation of a face as the caller gave it, and its validation.
#include <string>
#include <vector>

#include "wefm/core/mesh/halfedges.hpp"
#include "wefm/core/sys/types.hpp"

namespace wefm {

struct TriMesh {
  std::vector<Vec3> vertices;
  std::vector<Tri> triangles;
};

// Counts of what wefm_mesh_info reports; computed without rejecting anything.
struct MeshStats {
  std::int64_t boundary_loops = 0, components = 0, genus = 0;
  std::int64_t non_manifold_edges = 0, non_manifold_vertices = 0, degenerate_triangles = 0;
  std::int64_t duplicate_triangles = 0, inconsistent_edges = 0, bad_indices = 0, non_finite = 0;
  std::int64_t repeated_vertex_triangles = 0, isolated_vertices = 0;
  Vec3 bbox_min = Vec3::Zero(), bbox_max = Vec3::Zero();
  double area = 0.0, mean_edge_length = 0.0;
};

MeshStats compute_stats(const TriMesh& mesh);

// The diagonal of the finite vertices' bounding box (compute_stats' bbox), without the topology.
double bbox_diagonal(const TriMesh& mesh);

// Throws Error(invalid_mesh) naming the first offending vertex/triangle/edge. Accepts zero-area
// triangles (they are regularised by min_beta) and unreferenced vertices (they get no use).
// Returns the half-edges it built, so that the topology need not build them again.
HalfEdges validate_mesh(const TriMesh& mesh);

double triangle_area(const TriMesh& mesh, Index t);

}  // namespace wefm
