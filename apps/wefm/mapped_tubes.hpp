#pragma once
// `wefm mesh-model`: thin tubes (a wire, a pin, a pipe narrower than the size) meshed as mapped
// strips. A free mesh of a tube a few elements round must keep its elements about as long as they
// are wide, so a long wire costs thousands of triangles, and with fewer than four round it folds
// onto itself; a mapped strip keeps the round count of its end circles and stretches its elements
// along the axis, where the tube does not curve.
#include <map>
#include <set>
#include <vector>

#include "cad_edge_nodes.hpp"

namespace wefm_cli {

// Elements along a mapped tube are this many times as long as its ends' segments: the right
// triangles a quad of sides 1 and 2 splits into have Lo lambda 0.69.
constexpr double kTubeAspect = 2;
// The fewest segments round a mapped tube: three make a prism, which a mapped strip meshes without
// folding (a free mesh that few round reaches round to its own other side).
constexpr size_t kFewestRound = 3;

// The faces (CadModel::faces indices) to mesh as mapped strips: one loop made of a seam, one end (a
// circle or a chain of arcs), the seam back and the other end; both ends with as many segments, at
// least kFewestRound; the face given a size below h (narrow or curved). Ends that differ by at most
// a factor of two are made alike first: the end with fewer segments is re-discretised in
// `edge_nodes` to the other's count (each of its edges evenly, shares by length), unless it is an
// end of a tube mapped before (whose ends would then differ). Each such face's seam, used
// by no other face, is re-discretised in `edge_nodes` at kTubeAspect times the ends' segment length,
// at most h. Whether the strip can be mapped is the library's to say (four corners, opposite sides
// with as many nodes): where it cannot, the face is meshed free on the same edge nodes.
std::set<size_t> map_thin_tubes(const wefm_cad::CadModel& model, double h, const std::vector<double>& face_sizes,
                                std::map<long long, wefm_cad::EdgeNodes>& edge_nodes);

}  // namespace wefm_cli
