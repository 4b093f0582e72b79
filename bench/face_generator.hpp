#pragma once
// Deterministic scaling faces for the benchmark: the same (shape, size) always gives the same
// vertices and triangles, bit for bit, so figures from different runs and machines describe the
// same input. No random numbers: every coordinate is a closed-form function of the grid indices.
#include <cstdint>
#include <string>
#include <vector>

namespace wefm_bench {

enum class Shape {
  BumpyDisk,   // height field over a disk: one boundary loop, non-developable everywhere
  HoledPlate,  // doubly curved rectangular plate with three round holes: four boundary loops
  SeamedTube,  // bumpy open tube with a seam along one generator: two loops, one repeated edge
};

struct Face {
  std::vector<double> xyz;   // 3 per vertex
  std::vector<int32_t> tri;  // 3 per triangle, counter-clockwise seen from +z (the tube: from outside)
  std::vector<int32_t> seam; // 2 per facet edge to cut along (wefm_face_add_seams); empty: none
  int64_t vertices() const { return static_cast<int64_t>(xyz.size() / 3); }
  int64_t triangles() const { return static_cast<int64_t>(tri.size() / 3); }
};

// Builds a face with about `target_triangles` triangles (within a few percent: the grids are
// regular, so the count moves in steps). `cut`: the seam's facet edges split into two boundary
// sides (its vertices doubled), for peers that need a topological disk; the seam list is then empty.
Face generate(Shape shape, int64_t target_triangles, bool cut = false);

// "disk" / "plate" / "tube"; parse_shape returns false for an unknown name.
const char* shape_name(Shape shape);
bool parse_shape(const std::string& name, Shape& shape);

// "10k", "1M", "4M", or a plain number; returns false when the text is not a positive size.
bool parse_size(const std::string& text, int64_t& size);
std::string size_label(int64_t size);

// Plain OBJ (v and f lines), numbers written with std::to_chars so they read back exactly.
// Returns false with errno set when the file cannot be written.
bool write_obj(const std::string& path, const Face& face);
// The seam as `wefm flatten --seams` reads it: one facet edge per line, two 0-based vertex indices.
bool write_seam(const std::string& path, const Face& face);

// Binary STL (float32 corners, no shared vertices): what a reader must merge back.
bool write_stl(const std::string& path, const Face& face);

}  // namespace wefm_bench
