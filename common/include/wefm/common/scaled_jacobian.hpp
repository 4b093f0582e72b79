#pragma once
// The scaled Jacobian of a quad in 3D, the measure of every quad the project makes or checks: the
// smallest, over the four corners, of the corner's cross product (e1 x e2) against the quad's mean
// normal n (the normalised sum of the four), over |e1| |e2|. 1 for a rectangle, 0 for a corner of 0
// or 180 degrees, negative for a folded or inverted quad. Written once for the library's mesher and
// reports (core/meshing/mesh_quality) and the tool's model reports, so both judge a quad alike.
#include <cmath>

namespace wefm_common {

// `P` is any point whose coordinates are p[0], p[1], p[2]: a `const double*`, an Eigen 3-vector.
// Corners a, b, c, d in order round the quad.
template <class P>
inline double scaled_jacobian(const P& a, const P& b, const P& c, const P& d) {
  const P* p[4] = {&a, &b, &c, &d};
  double cr[4][3], len[4], n[3] = {0, 0, 0};
  for (int k = 0; k < 4; ++k) {
    const P& o = *p[k];
    const P& u = *p[(k + 1) % 4];
    const P& w = *p[(k + 3) % 4];
    const double e1[3] = {u[0] - o[0], u[1] - o[1], u[2] - o[2]};
    const double e2[3] = {w[0] - o[0], w[1] - o[1], w[2] - o[2]};
    cr[k][0] = e1[1] * e2[2] - e1[2] * e2[1];
    cr[k][1] = e1[2] * e2[0] - e1[0] * e2[2];
    cr[k][2] = e1[0] * e2[1] - e1[1] * e2[0];
    len[k] = std::sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]) * std::sqrt(e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2]);
    for (int i = 0; i < 3; ++i) n[i] += cr[k][i];
  }
  const double norm = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (!(norm > 0)) return 0;
  for (double& x : n) x /= norm;
  double worst = 1;
  for (int k = 0; k < 4; ++k) {
    const double q = len[k] > 0 ? (cr[k][0] * n[0] + cr[k][1] * n[1] + cr[k][2] * n[2]) / len[k] : 0.0;
    worst = q < worst ? q : worst;
  }
  return worst;
}

}  // namespace wefm_common
