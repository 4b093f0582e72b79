#pragma once
// The format readers behind read_mesh (one file each). All are our own parsers: they keep doubles
// exact (OpenMesh's OFF/PLY readers go through float), run at memory speed on million-triangle
// files, and name the line or element of any error.
#include <string>
#include <vector>

#include "wefm/core/mesh/mesh_io.hpp"

namespace wefm::io {

ReadResult read_obj(const std::string& path);
ReadResult read_stl(const std::string& path, double merge_tolerance);
ReadResult read_off(const std::string& path);
ReadResult read_ply(const std::string& path);

// STL corners (3 per triangle) to shared vertices: exact duplicates, then corners within
// `merge_tolerance` x bounding-box diagonal (<= 0: 1e-9). merged_vertices = corners - vertices.
ReadResult merge_corners(const std::vector<Vec3>& corners, double merge_tolerance, const std::string& path);

// Appends the fan triangulation of a polygon (v0 v1 v2, v0 v2 v3, ...).
inline void add_fan(std::vector<Tri>& triangles, const Index* poly, std::size_t n) {
  for (std::size_t k = 1; k + 1 < n; ++k) triangles.push_back({poly[0], poly[k], poly[k + 1]});
}

}  // namespace wefm::io
