#pragma once
// Virtual topology for `wefm mesh-model` (the paper's §1.2: geometry is abstracted before meshing).
// A face far narrower than the element size (a thin chamfer, a small fillet, a needle left by a
// modelling step) cannot get well-shaped triangles of its own: its edges' nodes are spaced at the
// size, and a triangle across a strip of width w with sides near h has Lo lambda about 2 w / h.
// Such a face is merged, for meshing only, with the neighbour across its smoothest shared edge: the
// two triangulations become one CadFace (the shared chain vertices are merged, the shared edges
// leave the loops, the loops are spliced), the shared edges get no nodes and the merged facets are
// flattened and meshed as one face. Its triangles are handed back to the original faces afterwards
// (triangle_faces), so the output keeps one group per B-rep face. A face with a corner under 12
// degrees (no triangle there can reach Lo lambda 0.3) is merged the same way with the neighbour
// across one of the corner's edges. A merge is kept only if the library flattens and meshes the
// merged face on its own at its size with min lambda 0.3.
#include <array>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cad_model.hpp"
#include "face_corners.hpp"

namespace wefm_cli {

// What was done to one narrow or sharp-cornered face: merged into another, or left alone.
struct FaceMerge {
  int face = 0;          // the merged face (CadFace::index)
  int into = 0;          // the face it was merged into (the virtual face keeps that one's index);
                         // 0: left alone (reason says why)
  double width = 0;      // 2 area / perimeter of the face, model units
  double dihedral = 0;   // largest angle between the facet normals across the shared edges, degrees
  std::vector<long long> shared_edges;  // model edge ids left out of the mesh
  std::string reason;
};

// Per virtual face (by position in the model's faces after merge_narrow_faces): the original face
// index of each of its facets, for faces that absorbed others; empty for a face left alone.
struct VirtualTopology {
  std::vector<FaceMerge> merges;
  std::vector<std::vector<int>> facet_face;
};

// Replaces the faces of `model` narrower than h / 30 (2 area / perimeter), and those with a corner
// under 12 degrees, by their merge with a neighbour (see virtual_faces.cpp for the rule); the faces keep their order. `face_sizes` (one per
// face) follows: a merged face keeps the size of the face that absorbed the narrow one, its own
// before the merge (the narrow facets' curvature and width would otherwise shrink it).
VirtualTopology merge_narrow_faces(wefm_cad::CadModel& model, double h, std::vector<double>& face_sizes);

// Per triangle of a virtual face's mesh, the original face it lies on: the absorbed face whose
// facet is under the triangle's centroid (within h / 2), else the face that kept its index. Empty
// for a face that absorbed none.
std::vector<int> triangle_faces(const VirtualTopology& vt, size_t virtual_face, const wefm_cad::CadFace& face,
                                const std::vector<double>& xyz, const std::vector<int32_t>& tris, double h);

// A corner this sharp caps every triangle in it below Lo lambda 0.3 (0.296 at 10 degrees: a triangle
// with an angle t has lambda at most 2 sqrt(3) sin t / (2 + 4 sin^2(t / 2))), whatever the mesh.
constexpr double kFloorCornerDegrees = 10;

// The report's list of merges (face, merged_into, reason, width, dihedral_degrees, shared_edges),
// and the faces merged into one face.
nlohmann::ordered_json merges_json(const VirtualTopology& vt);
std::vector<int> merged_into(const VirtualTopology& vt, int face);

}  // namespace wefm_cli
