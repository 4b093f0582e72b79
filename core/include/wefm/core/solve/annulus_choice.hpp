#pragma once
// An automatically cut annulus is also solved uncut (the boundary term alone keeps the two loops
// apart), and the better score is kept. The cut usually wins: a cylinder or a cone band is exact only
// cut, and a flat ring is exact cut too (the seam glued back, scar). The uncut face is solved
// conformally first and solved fully only if it beats the cut's conformal score: at most one more
// full solve, usually one more factorisation.
#include "wefm/core/solve/flatten.hpp"

namespace wefm {

// `cut_in` and `cut_res` are the solve on the cut topology `cut`; `uncut_spec` the caller's spec
// without the cut. If the uncut layout scores higher, cut_res takes it, expressed on the cut's uses
// (the seam's two sides coincide, so its mode reads scar). The report keeps the other layout's best score (conformal if it lost there). A failed
// uncut solve leaves cut_res as it was; cancellation propagates.
void keep_uncut_if_better(const TriMesh& mesh, const TopologySpec& uncut_spec, const Topology& cut, const FlattenInput& cut_in,
                          FlattenResult& cut_res);

}  // namespace wefm
