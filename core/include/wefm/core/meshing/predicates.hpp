#pragma once
// Robust geometric predicates for the UV triangulation: a floating-point evaluation with an error
// bound (after Shewchuk's filter idea), and an exact expansion evaluation when the bound does not
// settle the sign. Only the sign is exact; the magnitude is the plain floating-point value.
#include "wefm/core/sys/types.hpp"

namespace wefm::meshing {

using P2 = Eigen::Vector2d;

// > 0 when a, b, c turn counter-clockwise, < 0 clockwise, 0 exactly collinear.
double orient2d(const P2& a, const P2& b, const P2& c);
// > 0 when d lies strictly inside the circle through a, b, c (counter-clockwise), 0 on it.
double incircle(const P2& a, const P2& b, const P2& c, const P2& d);

}  // namespace wefm::meshing
