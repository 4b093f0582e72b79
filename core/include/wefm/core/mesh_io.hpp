#pragma once
// Reading triangle meshes from files and writing flattened faces.
#include <string>

#include "wefm/core/topology.hpp"

namespace wefm {

struct ReadResult {
  TriMesh mesh;
  std::int64_t merged_vertices = 0;  // STL: corners merged into shared vertices beyond exact matches
};

// OBJ (own parser, fast), STL ascii/binary (own parser, so merging is counted exactly), OFF and PLY
// (OpenMesh). Polygons are fan-triangulated. Throws Error(io) or Error(unsupported).
ReadResult read_mesh(const std::string& path, double merge_tolerance);

// OBJ with v (3D), vt (UV per use) and f v/vt.
void write_obj_uv(const std::string& path, const TriMesh& mesh, const Topology& topo, const VectorXc& uv);

}  // namespace wefm
