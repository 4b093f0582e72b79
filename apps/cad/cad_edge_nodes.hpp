#pragma once
// The first step of whole-model meshing (the paper's §1.2): every model edge is discretised once in
// 3D, so the faces sharing it get the very same nodes and the face meshes conform. Nodes are placed
// at equal arc length along the edge's facet chain, so they lie on the chain as
// wefm_face_set_edge_nodes requires; the chain is the same polyline in every face that uses the edge
// (BRepMesh discretises an edge once for the whole model).
#include <array>
#include <map>
#include <vector>

#include "cad_model.hpp"

namespace wefm_cad {

struct EdgeNodes {
  std::vector<double> xyz;  // 3 per node, in the edge's direction, both end vertices included
  // Segments between the nodes (0 for fewer than two nodes).
  long long segments() const { return xyz.size() < 6 ? 0 : static_cast<long long>(xyz.size() / 3) - 1; }
};

// Local size per face (by CadModel::faces index): a face narrower than h gets 2.5 times its width
// (Lo lambda about 0.6 on the triangles across it, instead of elements stretched over it), a
// curved face at most its smaller radius of curvature. Width = 2 area / perimeter (the width of a
// long strip, the radius of a disk). Floored by a budget of segments along the face's boundary
// (the model's needles share 40,000, each at least 2,000), between h / 300 and h / 8: a needle face
// cannot ask for millions of elements along its long edges. A face narrow only in part is left to
// the edges' local sizes (discretise_model_edges).
std::vector<double> local_face_sizes(const CadModel& model, double h);

// The 3D length of an edge's facet chain in a face.
double chain_length(const CadFace& face, const CadEdge& edge);

// The area of a face's tessellation.
double face_area(const CadFace& face);

// A face's width: 2 area / perimeter over its loops (a seam counts twice, as it bounds the domain
// twice): the width of a long strip, the radius of a disk. NaN when the loops have no length.
double face_width(const CadFace& face);

// Nodes along an edge's facet chain at `segments` (>= 1) equal steps of its 3D arc length.
EdgeNodes uniform_edge_nodes(const CadFace& face, const CadEdge& edge, long long segments);

// The same edge's nodes at `segments` (>= 1) segments, spaced as `nodes` were (graded the same way
// along the edge): node j goes where node j n / segments of the n old ones was, between old nodes
// at the fraction of the way. For matching counts (mapped faces' opposite sides) without losing the
// grading the edge's neighbours asked for.
EdgeNodes recount_edge_nodes(const CadFace& face, const CadEdge& edge, const EdgeNodes& nodes, long long segments);

// Per model edge id: its nodes (at least one segment; at least three for a closed edge, so a circle
// stays a polygon) at the smallest size of the faces that use it (`face_sizes`, one per face, or
// empty for h everywhere). Degenerate edges get no entry. With `gradation` g > 0 the segments also
// shrink where a face that has the edge is narrower than them (a strip, a slot, a corner sharper
// than about 20 degrees: 2.5 times the width across, down to h / 300 at a pinch, else h / 32; not
// within h / 2 of one of the `cusps`) and towards a model vertex where another edge has shorter
// ones, growing back by g per unit length (1 + g per segment, roughly); 0 keeps them uniform.
// `cusps` are the corners too sharp for any good triangle (under 10 degrees): shorter segments
// beside one only narrow its triangles' angle there, as the chords turn towards the edges' common
// tangent. Beyond the first segment from a cusp, which is the same on both its edges, they grow
// as a fan: each 2.5 times the width across the corner where it starts, so that the triangles
// across the corner behind its tip keep their shape.
// Where a side of the corner is a single segment, the fan goes on along the next edge of the loop
// (`beyond`).
struct Cusp {
  std::array<double, 3> point;
  double degrees = 0;
  std::array<long long, 2> edges{{-1, -1}};   // the model edges meeting at the corner
  std::array<long long, 2> beyond{{-1, -1}};  // per side, the edge of the loop past its far end, or -1
};
std::map<long long, EdgeNodes> discretise_model_edges(const CadModel& model, double h,
                                                      const std::vector<double>& face_sizes = {}, double gradation = 0,
                                                      const std::vector<Cusp>& cusps = {});

}  // namespace wefm_cad
