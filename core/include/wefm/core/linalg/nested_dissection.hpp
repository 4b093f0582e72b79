#pragma once
// A fill-reducing elimination order by geometric nested dissection: the unknowns (points of a
// surface mesh, with the graph of a symmetric matrix over them) are split at the median along the
// longest side of their bounding box; the points of the upper half with a neighbour in the lower
// half form the separator, ordered after both halves, which are split the same way down to `leaf`
// points (kept in their order). The separators are taken on the graph given, so couplings beyond
// the triangles (the boundary term's, two steps along a loop) are separated too.
//
// Why: on a large disk the boundary term's couplings make minimum degree's fill poor and CHOLMOD
// then runs METIS, whose analysis is a large share of the solve; this order costs a small fraction
// of that for about the same fill (docs/PERFORMANCE.md, "Measurements behind design choices").
#include <vector>

#include "wefm/core/sys/types.hpp"

namespace wefm {

// outer/inner: the graph in CSC form (column j's neighbours inner[outer[j] .. outer[j + 1]), both
// directions; self loops ignored). xyz: a point per unknown. Returns perm with perm[k] the unknown
// eliminated k-th (CHOLMOD's UserPerm). Deterministic: ties go by index.
std::vector<int> geometric_nested_dissection(const int* outer, const int* inner, const std::vector<Vec3>& xyz, int leaf = 16);

}  // namespace wefm
