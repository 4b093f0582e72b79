#include "wefm/core/method/coefficients.hpp"
#include "wefm/core/sys/huge_pages.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>

#include "wefm/core/sys/parallel.hpp"
#include "wefm/core/mesh/use_corners.hpp"

namespace wefm {

Coefficients compute_coefficients(const TriMesh& m, const Topology& tp, bool curvature_adjust, double min_beta, int threads) {
  Coefficients c;
  const size_t nt = m.triangles.size(), nh = 3 * nt;
  auto vertex = [&](size_t t, int j) -> const Vec3& { return m.vertices[static_cast<size_t>(m.triangles[t][static_cast<size_t>(j)])]; };
  // One running sum in half-edge order, in the caller's thread (about 1% of this function): the
  // length scale enters every coefficient, and keeping it to the bit keeps results to the bit.
  double total = 0;
  for (size_t t = 0; t < nt; ++t)
    for (int j = 0; j < 3; ++j) total += (vertex(t, (j + 1) % 3) - vertex(t, j)).norm();
  c.length_scale = total > 0 ? total / static_cast<double>(nh) : 1.0;
  const double inv = 1.0 / c.length_scale;
  for (std::vector<double>* v : {&c.alpha, &c.beta, &c.length, &c.corner_angle}) {
    assign_huge(*v, nh);
  }
  c.tri_area.resize(nt);
  c.use_angle.assign(static_cast<size_t>(tp.use_count), 0.0);
  c.use_area.assign(static_cast<size_t>(tp.use_count), 0.0);
  std::vector<double> raw_beta;
  assign_huge(raw_beta, nh);
  std::atomic<Index> degenerate{0};
  parallel_for(threads, static_cast<Index>(nt), [&](Index t0, Index t1) {
    Index zero_area = 0;
    for (size_t t = static_cast<size_t>(t0); t < static_cast<size_t>(t1); ++t) {
      Vec3 p[3];
      for (int j = 0; j < 3; ++j) p[j] = vertex(t, j) * inv;
      const double area = 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).norm();
      c.tri_area[t] = area;
      if (!(area > 0)) ++zero_area;
      for (int j = 0; j < 3; ++j) {
        const size_t h = 3 * t + static_cast<size_t>(j);
        const Vec3 e = p[(j + 1) % 3] - p[j], g = p[(j + 2) % 3] - p[j];
        const double L2 = e.squaredNorm();
        const double cross = e.cross(g).norm(), dot = e.dot(g);
        c.length[h] = std::sqrt(L2);
        if (L2 > 0) {
          c.alpha[h] = dot / L2;
          raw_beta[h] = cross / L2;
        } else {
          c.alpha[h] = 0.5;  // coincident end points: no direction to measure along
          raw_beta[h] = 0.0;
        }
        // Angle at corner j between edges to j+1 and j+2; atan2 stays accurate for needles.
        c.corner_angle[h] = std::atan2(cross, dot);
      }
    }
    degenerate += zero_area;
  });
  c.degenerate_triangles = degenerate;
  // Per-use sums gathered in corner order (see use_corners.hpp).
  const UseCorners uc = use_corners(tp);
  parallel_for(threads, tp.use_count, [&](Index u0, Index u1) {
    for (Index u = u0; u < u1; ++u) {
      double angle = 0.0, area = 0.0;
      for (Index k = uc.start[static_cast<size_t>(u)]; k < uc.start[static_cast<size_t>(u) + 1]; ++k) {
        const Index h = uc.corner[static_cast<size_t>(k)];
        angle += c.corner_angle[static_cast<size_t>(h)];
        area += c.tri_area[static_cast<size_t>(h / 3)];
      }
      c.use_angle[static_cast<size_t>(u)] = angle;
      c.use_area[static_cast<size_t>(u)] = area;
    }
  });
  std::atomic<Index> floored{0};
  parallel_for(threads, static_cast<Index>(nh), [&](Index h0, Index h1) {
    Index raised = 0;
    for (Index h = h0; h < h1; ++h) {
      const Index opp = tp.corner_use[static_cast<size_t>(HalfEdges::prev(h))];
      double f = 1.0;
      if (curvature_adjust && !tp.use_on_loop[static_cast<size_t>(opp)]) f = c.use_angle[static_cast<size_t>(opp)] / (2 * kPi);
      double b = raw_beta[static_cast<size_t>(h)] * f;
      if (!(b >= min_beta)) {
        b = min_beta;
        ++raised;
      }
      c.beta[static_cast<size_t>(h)] = b;
    }
    floored += raised;
  });
  c.floored = floored;
  return c;
}

}  // namespace wefm
