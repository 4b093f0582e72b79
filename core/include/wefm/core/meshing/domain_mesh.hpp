#pragma once
// A mesh of the solved domain and its image in 3D (METHOD §9): the entry point of meshing.
#include <array>
#include <string>
#include <vector>

#include "wefm/core/meshing/boundary.hpp"
#include "wefm/core/meshing/mesh_control.hpp"
#include "wefm/core/meshing/mesh_options.hpp"

namespace wefm::meshing {

struct DomainMesh {
  std::vector<P2> uv;
  std::vector<Vec3> xyz;
  // Surface normal at each node: free meshes interpolate vertex normals; transfinite meshes use the
  // grid's own normal (cross product of the two rail directions).
  std::vector<Vec3> normal;
  int nodes_per_element = 3;
  std::vector<Index> elements;  // nodes_per_element per element, counter-clockwise in UV
  // Transfinite: interior grid lines (rows j = 1..m-1 over i, then columns i = 1..n-1 over j) in the
  // grid numbering j * (n + 1) + i; empty for free meshes.
  std::vector<std::vector<Index>> rails;
  Index grid_columns = 0;  // transfinite: n + 1
  Index boundary_nodes = 0;                // nodes 0..boundary_nodes-1 lie on the loops
  // Free meshes: edges inside the face that stay edges of the mesh (hard_edges.hpp), each once, both
  // ends boundary nodes: the segments of every scar.
  std::vector<std::array<Index, 2>> hard_edges;
  MeshReport report;
};

// Needs a solved face: `uv` holds the UV of every use. Throws Error(invalid_argument) on bad
// options and Error(unsupported) for transfinite meshing of a face with holes or too few corners.
// `control` stops it (Error(cancelled)) and hears its progress: 0 at the start, the boundary's
// discretisation by 0.1, node insertion up to 0.8, smoothing up to 0.95, 1 when done.
DomainMesh mesh_domain(const TriMesh& mesh, const Topology& topo, const VectorXc& uv, const MeshOptions& options,
                       const EdgeNodes& given = {}, const MeshControl& control = {});

// OBJ of a domain mesh: v (3D) and vt (UV) per node, f v/vt per element (triangles or quads),
// replaced whole or not at all. Throws Error(io) naming the file.
void write_obj(const std::string& path, const DomainMesh& mesh);

}  // namespace wefm::meshing
