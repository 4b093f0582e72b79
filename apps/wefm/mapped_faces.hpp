#pragma once
// `wefm mesh-model`: mapped (transfinite) meshing where the geometry allows it, found automatically,
// with the node counts of opposite sides matched across the whole model (the paper's §1.2: "match
// the number of vertices on matched edges for the whole system"). A face is four-sided when its one
// loop turns at exactly four corners (docs/METHOD.md §9.7); a transfinite grid needs its opposite
// sides to have as many segments, and since every model edge is discretised once for all the faces
// that use it, one face's sides tie its edges' counts to those of every other mapped face.
#include <array>
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "cad_edge_nodes.hpp"

namespace wefm_cli {

// A corner of a four-sided face turns the loop by at least 30 degrees: its inside angle is at most
// this. Below kFewestCornerDegrees a grid cell there has a scaled Jacobian under 0.5.
constexpr double kCornerDegrees = 150;
constexpr double kFewestCornerDegrees = 30;
// Where edges meet along a side the loop turns by less than this (degrees either way): a side may
// be a chain of edges that continue each other. A turn between this and a corner's is neither, and
// the face is not taken for four-sided.
constexpr double kSmoothTurnDegrees = 20;
// Opposite sides longer than this many times the other would give cells of very different sizes
// at the two ends of the grid.
constexpr double kSideRatio = 3;

// The four sides of a four-sided face, in loop order from a corner.
struct FourSides {
  std::array<std::vector<long long>, 4> edges;  // model edge ids of each side (a seam is on two sides)
  std::array<double, 4> length{};               // each side's 3D length
  std::array<int32_t, 4> corners{};             // the corners' vertices in the face's xyz, in loop order
};

// True with `sides` when the face has one loop, no degenerate edge (a pole), four corners between
// kFewestCornerDegrees and kCornerDegrees inside and only smooth turns between them, and opposite
// sides within kSideRatio of each other; else false with `why`.
bool four_sides(const wefm_cad::CadFace& f, FourSides& sides, std::string& why);

// What map_four_sided_faces did.
struct MappedFaces {
  std::set<size_t> faces;                 // CadModel::faces indices to mesh mapped
  std::map<size_t, FourSides> sides;      // of the four-sided ones among them
  size_t four_sided = 0;                  // faces found four-sided (named ones included)
  std::map<size_t, std::string> refused;  // four-sided or named, not mapped: why
  std::set<long long> recounted;          // model edges given another segment count
};

// Segment counts only grow, so no element gets longer than its size: an edge may go up to twice
// its count (plus one) to match, no further.
constexpr double kMostGrowth = 2;

// The mapped four-sided faces whose opposite sides do not have as many segments in `edge_nodes`
// (none right after map_four_sided_faces; nodes added to edges later can make some).
size_t mismatched_faces(const MappedFaces& m, const std::map<long long, wefm_cad::EdgeNodes>& edge_nodes);

// Picks the faces to mesh mapped, `named` ones first (CadModel::faces indices; any face the caller
// named, four-sided or not), then with `automatic` every other four-sided face, largest first, and
// matches the segment counts of their opposite sides across the model: each face is taken if the
// counts of the faces taken so far, and its own, can be matched by adding segments to edges
// (kMostGrowth), else left free. The edges of `fixed` faces (mapped tubes, already matched) keep
// their counts. A face with an edge in `unsettled` (one whose nodes change after planning: those of
// faces lying on each other, which take each other's nodes) is not mapped automatically. Edges
// given another count are re-discretised in `edge_nodes`, graded as before.
MappedFaces map_four_sided_faces(const wefm_cad::CadModel& model, const std::vector<size_t>& named, bool automatic,
                                 const std::set<size_t>& fixed, const std::set<long long>& unsettled,
                                 std::map<long long, wefm_cad::EdgeNodes>& edge_nodes);

}  // namespace wefm_cli
