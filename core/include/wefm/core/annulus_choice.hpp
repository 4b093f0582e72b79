#pragma once
// An automatically cut annulus is solved twice: cut (the solver decides the seam's mode, periodic for
// a cylinder) and uncut (the boundary term alone keeps the two loops apart). Neither wins
// everywhere: a cylinder is exact only cut, a flat ring only uncut. The better score is kept.
#include "wefm/core/flatten.hpp"

namespace wefm {

// `cut_in` and `cut_res` are the solve on the cut topology `cut`; `uncut_spec` the caller's spec
// without the cut. If the uncut layout scores higher, cut_res takes it, expressed on the cut's uses
// (the seam's two sides coincide, so its mode reads scar). The report keeps the other layout's score. A failed
// uncut solve leaves cut_res as it was; cancellation propagates.
void keep_uncut_if_better(const TriMesh& mesh, const TopologySpec& uncut_spec, const Topology& cut, const FlattenInput& cut_in,
                          FlattenResult& cut_res);

}  // namespace wefm
