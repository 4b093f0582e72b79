#include "wefm/core/coefficients.hpp"

#include <algorithm>
#include <cmath>

namespace wefm {

Coefficients compute_coefficients(const TriMesh& m, const Topology& tp, bool curvature_adjust, double min_beta) {
  Coefficients c;
  const size_t nt = m.triangles.size(), nh = 3 * nt;
  double total = 0;
  for (const Tri& t : m.triangles)
    for (int j = 0; j < 3; ++j) total += (m.vertices[static_cast<size_t>(t[(j + 1) % 3])] - m.vertices[static_cast<size_t>(t[j])]).norm();
  c.length_scale = total > 0 ? total / static_cast<double>(nh) : 1.0;
  const double inv = 1.0 / c.length_scale;
  c.alpha.resize(nh);
  c.beta.resize(nh);
  c.length.resize(nh);
  c.corner_angle.resize(nh);
  c.tri_area.resize(nt);
  c.use_angle.assign(static_cast<size_t>(tp.use_count), 0.0);
  c.use_area.assign(static_cast<size_t>(tp.use_count), 0.0);
  std::vector<double> raw_beta(nh);
  for (size_t t = 0; t < nt; ++t) {
    const Tri& f = m.triangles[t];
    Vec3 p[3];
    for (int j = 0; j < 3; ++j) p[j] = m.vertices[static_cast<size_t>(f[j])] * inv;
    const double area = 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).norm();
    c.tri_area[t] = area;
    if (!(area > 0)) ++c.degenerate_triangles;
    for (int j = 0; j < 3; ++j) {
      const size_t h = 3 * t + static_cast<size_t>(j);
      const Vec3 e = p[(j + 1) % 3] - p[j], g = p[(j + 2) % 3] - p[j];
      const double L2 = e.squaredNorm();
      c.length[h] = std::sqrt(L2);
      if (L2 > 0) {
        c.alpha[h] = e.dot(g) / L2;
        raw_beta[h] = e.cross(g).norm() / L2;
      } else {
        c.alpha[h] = 0.5;  // coincident end points: no direction to measure along
        raw_beta[h] = 0.0;
      }
      // Angle at corner j between edges to j+1 and j+2; atan2 stays accurate for needles.
      const Vec3 a = p[(j + 1) % 3] - p[j], b = p[(j + 2) % 3] - p[j];
      c.corner_angle[h] = std::atan2(a.cross(b).norm(), a.dot(b));
      const Index u = tp.corner_use[h];
      c.use_angle[static_cast<size_t>(u)] += c.corner_angle[h];
      c.use_area[static_cast<size_t>(u)] += area;
    }
  }
  for (size_t h = 0; h < nh; ++h) {
    const Index opp = tp.corner_use[HalfEdges::prev(static_cast<Index>(h))];
    double f = 1.0;
    if (curvature_adjust && !tp.use_on_loop[static_cast<size_t>(opp)]) f = c.use_angle[static_cast<size_t>(opp)] / (2 * kPi);
    double b = raw_beta[h] * f;
    if (!(b >= min_beta)) {
      b = min_beta;
      ++c.floored;
    }
    c.beta[h] = b;
  }
  return c;
}

}  // namespace wefm
