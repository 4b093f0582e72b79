#pragma once
// Mesh improvement judged in 3D: edge flips and UV node moves are kept only when the worst Lo
// lambda of the 3D triangles they touch improves (the UV triangles must stay positive); then a few
// passes of optimise_nodes (node_optimisation.hpp) for the sum of log lambda; last, a triangle still
// below lambda 0.3 gets a node on its longest inner edge where that lifts the worst element near it
// (a needle across a strip narrower than h has no interior node to move). Boundary nodes never move
// and are never added: faces sharing an edge keep sharing its nodes.
#include <array>
#include <vector>

#include "wefm/core/meshing/hard_edges.hpp"
#include "wefm/core/meshing/mesh_control.hpp"
#include "wefm/core/meshing/surface_map.hpp"

namespace wefm::meshing {

// An edge inside the face between two boundary nodes whose middle lies on the surface farther than
// this fraction of its length from the edge's line spans the face instead of following it (a
// chord across a quarter-round fillet is 0.21 of its length from the arc, across a half tube 0.5).
// Across a half tube or the tip of a half cone such a chord lies where another face is (the
// symmetry plane of a half model), and the two faces' meshes then share edges and triangles. Size
// and quality never see it: in 3D the triangles on it are well shaped and no larger than h.
constexpr double kSpanSag = 0.25;
// With MeshOptions::split_chords: a tenth of the length, from any length. The caller knows that
// another face shares two of this face's boundary nodes, so a straight chord between them may be
// that face's edge too: a diagonal across a half tube twice as long as the tube is wide lies 0.24 of
// its length off the surface, and a coarse half tube's chords are shorter than half the size.
constexpr double kChordSag = 0.1;
// Two boundary nodes closer in 3D than this fraction of their UV distance are copies of one point
// (the two sides of a seam at a cone's apex or a pole): the domain keeps lengths near their 3D ones.
constexpr double kSamePoint = 1e-4;

// Whether nodes at UV ua, ub and 3D a, b are copies of one point (kSamePoint).
inline bool one_point(const P2& ua, const P2& ub, const Vec3& a, const Vec3& b) {
  return (b - a).squaredNorm() <= kSamePoint * kSamePoint * (ua - ub).squaredNorm();
}

// Which edges between two boundary nodes span the face: from `shortest` long, with the surface at
// their UV middle farther than `sag` of their length from their line.
struct SpanRule {
  double shortest = 0;
  double sag = kSpanSag;
};

// Whether the edge a-b (UV ua-ub) spans the face as above. By default edges shorter than half the
// size never do: at a sharp corner or a cusp short edges bulge as much, and splitting them leaves
// slivers where no other face lies (free_mesh). `middle`, if given, gets the surface point at the UV
// middle.
bool spans_face(const P2& ua, const P2& ub, const Vec3& a, const Vec3& b, const SurfaceMap& map, const SpanRule& rule,
                Vec3* middle = nullptr);

// Nodes below `fixed` (the boundary nodes) never move, and the `hard` edges between them are never
// flipped or split. Returns the number of accepted moves.
// `control` is checked before every pass (fractions 0.8 to 0.95): a stop throws Error(cancelled).
// Flips never make an edge that spans the face (spans_face by `span`), and the last pass splits
// those the moves left.
std::int64_t improve_in_3d(std::vector<P2>& uv, std::vector<Vec3>& xyz, std::vector<std::array<Index, 3>>& tris, Index fixed,
                           const HardEdges& hard, int iterations, const SurfaceMap& map, const MeshControl& control, const SpanRule& span);

}  // namespace wefm::meshing
