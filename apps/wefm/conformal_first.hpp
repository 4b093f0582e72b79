#pragma once
// `wefm mesh-model` flattens a face conformally first (its own faces and the trial meshes of merged
// faces alike): a conformal map keeps angles, so the mesher's well-shaped UV triangles stay well
// shaped on the surface, and its area distortion only rescales sizes, which the 3D size field
// absorbs; it is also one linear solve, where s = 1 needs a continuation (docs/PERFORMANCE.md,
// "Measurements behind design choices"). A conformal domain that is unusable, or that the mesher
// refuses, is flattened again at the command's s.
#include "wefm/wefm.h"

namespace wefm_cli {

constexpr double kConformalS = 0;

// Why a conformal flattening with this report is not meshed (a flipped triangle or a boundary
// crossing itself: a negative score), or null when it is usable.
inline const char* conformal_unusable(const wefm_report& report) {
  return report.score >= 0 ? nullptr : "flatten: the conformal domain has a flipped triangle or crosses itself";
}

}  // namespace wefm_cli
