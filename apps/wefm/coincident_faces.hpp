#pragma once
// Faces lying on each other (the touching faces of an assembly's volumes, a body the file holds
// twice) must be meshed alike, or their meshes cross each other. Candidates: the same area and
// bounding box of the facets (to 1e-6 of the model's diagonal, the area to 1e-6 of itself).
#include <array>
#include <cstddef>
#include <vector>

#include "cad_model.hpp"

namespace wefm_cli {

struct FaceShape {
  double area;
  std::array<double, 6> box;
  std::array<double, 3> normal;  // area-weighted sum of the facet normals
};

FaceShape shape_of(const wefm_cad::CadFace& f);

// Per face, the earlier face it lies on (index + 1; that face lies on no earlier one), or 0.
std::vector<size_t> coincident_faces(const wefm_cad::CadModel& model);

}  // namespace wefm_cli
