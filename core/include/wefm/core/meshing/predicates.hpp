#pragma once
// Robust geometric predicates for the UV triangulation: a floating-point evaluation with an error
// bound (after Shewchuk's filter idea), and an exact expansion evaluation when the bound does not
// settle the sign. Only the sign is exact; the magnitude is the plain floating-point value.
#include <cmath>
#include <limits>

#include "wefm/core/sys/types.hpp"

namespace wefm::meshing {

using P2 = Eigen::Vector2d;

// orient2d where the floating-point filter cannot settle the sign: the exact sign times |det|.
double orient2d_exact(const P2& a, const P2& b, const P2& c, double det);

// > 0 when a, b, c turn counter-clockwise, < 0 clockwise, 0 exactly collinear. The filter is
// inline: the triangulation and every inversion test call it in their innermost loops.
inline double orient2d(const P2& a, const P2& b, const P2& c) {
  // Error bound coefficient generously above Shewchuk's (3 + 16 e) e, e half the machine epsilon.
  constexpr double kOrientBound = 4.0 * (std::numeric_limits<double>::epsilon() * 0.5);
  const double l = (a.x() - c.x()) * (b.y() - c.y());
  const double r = (a.y() - c.y()) * (b.x() - c.x());
  const double det = l - r;
  const double bound = kOrientBound * (std::fabs(l) + std::fabs(r));
  if (std::fabs(det) > bound) return det;
  return orient2d_exact(a, b, c, det);
}
// > 0 when d lies strictly inside the circle through a, b, c (counter-clockwise), 0 on it.
double incircle(const P2& a, const P2& b, const P2& c, const P2& d);

}  // namespace wefm::meshing
