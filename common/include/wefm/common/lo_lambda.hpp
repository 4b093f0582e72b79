#pragma once
// Lo's triangle quality, the measure of every mesh the project makes or checks: 4 sqrt(3) area /
// (l1^2 + l2^2 + l3^2), 1 for an equilateral triangle, 0 for one without area. Written once for the
// library's mesher (smoothing and node optimisation evaluate it in their innermost loops, hence
// inline) and the tool's model checks and reports, so both judge a triangle alike.
#include <cmath>

namespace wefm_common {

// `P` is any point whose coordinates are p[0], p[1], p[2]: a `const double*`, an Eigen 3-vector.
template <class P>
inline double lo_lambda(const P& a, const P& b, const P& c) {
  const double e1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};  // a -> b
  const double e2[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};  // a -> c
  const double e3[3] = {c[0] - b[0], c[1] - b[1], c[2] - b[2]};  // b -> c
  const double nx = e1[1] * e2[2] - e1[2] * e2[1];
  const double ny = e1[2] * e2[0] - e1[0] * e2[2];
  const double nz = e1[0] * e2[1] - e1[1] * e2[0];
  const double area = 0.5 * std::sqrt(nx * nx + ny * ny + nz * nz);
  const double s = (e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]) + (e3[0] * e3[0] + e3[1] * e3[1] + e3[2] * e3[2]) +
                   (e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2]);
  return s > 0 ? 4.0 * std::sqrt(3.0) * area / s : 0.0;
}

}  // namespace wefm_common
