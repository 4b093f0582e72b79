#pragma once
// Reading triangle meshes from files and writing flattened faces.
#include <string>

#include "wefm/core/mesh/topology.hpp"

namespace wefm {

struct ReadResult {
  TriMesh mesh;
  std::int64_t merged_vertices = 0;  // STL: corners merged into an earlier vertex (exact or within tolerance)
};

// Own parsers for every format, so coordinates stay double (OpenMesh's OFF/PLY readers go through
// float) and a million-triangle file reads in a fraction of a second: OBJ, STL ascii/binary (corners
// merged, count exact), OFF (ASCII), PLY (ASCII and binary). Polygons are fan-triangulated.
// Throws Error(io) naming the file and line or element, or Error(unsupported).
ReadResult read_mesh(const std::string& path, double merge_tolerance);

// OBJ with v (3D), vt (UV per use) and f v/vt.
void write_obj_uv(const std::string& path, const TriMesh& mesh, const Topology& topo, const VectorXc& uv);

}  // namespace wefm
