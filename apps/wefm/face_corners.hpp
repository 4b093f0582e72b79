#pragma once
// The corners of a CAD face's loops, measured on its facets: where one edge use of a loop ends and
// the next begins, the angle inside the face. Narrow-face merging looks for corners too sharp for a
// good triangle (virtual_faces); mapped meshing for faces with four corners near right angles
// (mapped_faces).
#include <array>
#include <cstdint>
#include <vector>

#include "cad_model.hpp"

namespace wefm_cli {

// Radians to degrees, the unit of a face's corners and of the turns between faces.
inline double degrees(double radians) { return radians * 180 / 3.14159265358979323846; }

// The cross product of facet t's edges from its first corner: its normal (counter-clockwise seen
// from outside) times twice its area.
std::array<double, 3> facet_cross(const wefm_cad::CadFace& f, size_t t);

// The unit normal of facet t (counter-clockwise seen from outside); zero for a degenerate facet.
std::array<double, 3> facet_normal(const wefm_cad::CadFace& f, size_t t);

// A corner of a face: where two of its loop's edges meet (or a degenerate edge between them, a
// pole), the angle inside the face.
struct FaceCorner {
  double degrees = 0;                 // 180 less the loop's turn there, seen along the facets' normal
                                      // (a notch is 270, not 90): 0 to 360
  std::array<long long, 2> edges{};   // the ids of the model edges meeting there
  int32_t vertex = -1;                // the corner's vertex in the face's xyz
  size_t loop = 0, use = 0;           // the loop and the edge use (CadFace::loops) that ends there
};

// Every corner of the face's loops, loop by loop in loop order. None where two uses do not meet at
// one vertex or the facets give no normal there.
std::vector<FaceCorner> face_corners(const wefm_cad::CadFace& f);

// The face's corners sharper than `below` degrees, sharpest first.
std::vector<FaceCorner> sharp_corners(const wefm_cad::CadFace& f, double below);

// Per side of a corner (its two edges, in FaceCorner::edges order), the model edge of the loop past
// that side's far end (the one before the first, the one after the second; poles skipped), or -1
// where the loop has no other edge.
std::array<long long, 2> edges_beyond(const wefm_cad::CadFace& f, const FaceCorner& c);

}  // namespace wefm_cli
