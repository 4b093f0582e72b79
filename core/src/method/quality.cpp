#include "wefm/core/method/quality.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_set>

#include "wefm/core/sys/parallel.hpp"

namespace wefm {

namespace {

double cross2(Complex a, Complex b) { return a.real() * b.imag() - a.imag() * b.real(); }
double orient(Complex p, Complex q, Complex r) { return cross2(q - p, r - p); }

}  // namespace

std::int64_t count_boundary_intersections(const Topology& tp, const VectorXc& z) {
  struct Seg {
    Index a, b;
  };
  std::vector<Seg> segs;
  for (const auto& lu : tp.loop_uses)
    for (size_t j = 0; j < lu.size(); ++j) segs.push_back({lu[j], lu[(j + 1) % lu.size()]});
  if (segs.size() < 2) return 0;
  double xmin = 1e300, ymin = 1e300, xmax = -1e300, ymax = -1e300;
  for (const Seg& s : segs)
    for (Index u : {s.a, s.b}) {
      xmin = std::min(xmin, z[u].real());
      xmax = std::max(xmax, z[u].real());
      ymin = std::min(ymin, z[u].imag());
      ymax = std::max(ymax, z[u].imag());
    }
  if (!(std::isfinite(xmin) && std::isfinite(xmax) && std::isfinite(ymin) && std::isfinite(ymax))) return static_cast<std::int64_t>(segs.size());
  const double span = std::max(xmax - xmin, ymax - ymin);
  const double total = [&] {
    double t = 0;
    for (const Seg& s : segs) t += std::abs(z[s.b] - z[s.a]);
    return t;
  }();
  // Cells about the mean segment length keep each segment in O(1) cells and each cell at O(1) segments.
  double cell = std::max(total / static_cast<double>(segs.size()), span * 1e-9);
  if (!(cell > 0)) return 0;
  const double maxcells = 4.0 * static_cast<double>(segs.size()) + 16;
  while ((span / cell + 1) * (span / cell + 1) > maxcells * 64) cell *= 2;
  const std::int64_t nx = static_cast<std::int64_t>((xmax - xmin) / cell) + 1;
  std::vector<std::pair<std::int64_t, Index>> entries;
  for (Index k = 0; k < static_cast<Index>(segs.size()); ++k) {
    const Complex p = z[segs[static_cast<size_t>(k)].a], q = z[segs[static_cast<size_t>(k)].b];
    const std::int64_t i0 = static_cast<std::int64_t>((std::min(p.real(), q.real()) - xmin) / cell);
    const std::int64_t i1 = static_cast<std::int64_t>((std::max(p.real(), q.real()) - xmin) / cell);
    const std::int64_t j0 = static_cast<std::int64_t>((std::min(p.imag(), q.imag()) - ymin) / cell);
    const std::int64_t j1 = static_cast<std::int64_t>((std::max(p.imag(), q.imag()) - ymin) / cell);
    for (std::int64_t i = i0; i <= i1; ++i)
      for (std::int64_t j = j0; j <= j1; ++j) entries.emplace_back(j * nx + i, k);
  }
  std::sort(entries.begin(), entries.end());
  std::unordered_set<std::uint64_t> hits;
  for (size_t s = 0; s < entries.size();) {
    size_t e = s + 1;
    while (e < entries.size() && entries[e].first == entries[s].first) ++e;
    for (size_t x = s; x < e; ++x)
      for (size_t y = x + 1; y < e; ++y) {
        const Seg& A = segs[static_cast<size_t>(entries[x].second)];
        const Seg& B = segs[static_cast<size_t>(entries[y].second)];
        if (A.a == B.a || A.a == B.b || A.b == B.a || A.b == B.b) continue;
        const Complex p = z[A.a], q = z[A.b], r = z[B.a], t = z[B.b];
        if (orient(p, q, r) * orient(p, q, t) < 0 && orient(r, t, p) * orient(r, t, q) < 0) {
          const std::uint64_t k1 = static_cast<std::uint32_t>(std::min(entries[x].second, entries[y].second));
          const std::uint64_t k2 = static_cast<std::uint32_t>(std::max(entries[x].second, entries[y].second));
          hits.insert((k1 << 32) | k2);
        }
      }
    s = e;
  }
  return static_cast<std::int64_t>(hits.size());
}

Quality evaluate_quality(const TriMesh& m, const Topology& tp, const VectorXc& z, int threads) {
  Quality q;
  const size_t nt = m.triangles.size();
  const Index n = static_cast<Index>(nt);
  // Per-triangle terms in parallel, every sum afterwards in triangle order in one thread: the same
  // bits as a serial pass for any thread count (maxima do not depend on the order).
  std::vector<double> a3(nt), a2(nt);
  parallel_for(threads, n, [&](Index t0, Index t1) {
    for (size_t t = static_cast<size_t>(t0); t < static_cast<size_t>(t1); ++t) {
      const Tri& f = m.triangles[t];
      const Vec3 &p0 = m.vertices[static_cast<size_t>(f[0])], &p1 = m.vertices[static_cast<size_t>(f[1])], &p2 = m.vertices[static_cast<size_t>(f[2])];
      a3[t] = 0.5 * (p1 - p0).cross(p2 - p0).norm();
      const Complex u0 = z[tp.corner_use[3 * t]], u1 = z[tp.corner_use[3 * t + 1]], u2 = z[tp.corner_use[3 * t + 2]];
      a2[t] = 0.5 * cross2(u1 - u0, u2 - u0);
    }
  });
  double abs_uv = 0, wsum = 0;
  for (size_t t = 0; t < nt; ++t) {
    q.area_3d += a3[t];
    q.uv_area += a2[t];
    if (a2[t] < 0) ++q.flips;
    if (a3[t] > 0) wsum += a3[t];
  }
  for (double a : a2) abs_uv += std::abs(a);
  const double k = abs_uv > 0 ? q.area_3d / abs_uv : 0.0;  // area normalisation
  const double ls = std::sqrt(k);
  // Weighted terms, written over a3 (w ar) and a2 (w r^2) once read; triangles of zero 3D area
  // add exact zeros.
  std::vector<double> wang(nt);
  constexpr Index kMaxBlock = 65536;  // fixed blocks for the maxima, whatever the thread count
  const Index blocks = (n + kMaxBlock - 1) / kMaxBlock;
  std::vector<double> block_angle_max(static_cast<size_t>(blocks), 0.0), block_area_max(static_cast<size_t>(blocks), 0.0);
  parallel_for(
      threads, blocks,
      [&](Index blk0, Index blk1) {
        for (Index blk = blk0; blk < blk1; ++blk) {
          double angle_max = 0, area_max = 0;
          for (size_t t = static_cast<size_t>(blk * kMaxBlock); t < static_cast<size_t>(std::min(n, (blk + 1) * kMaxBlock)); ++t) {
            const double w = a3[t];
            if (!(w > 0)) {
              a3[t] = a2[t] = wang[t] = 0.0;
              continue;
            }
            const double ratio = std::abs(a2[t]) * k / w;
            const double r = ratio > 1 ? 1 / ratio : ratio;
            // Jacobian in a local frame of the 3D triangle.
            const Tri& f = m.triangles[t];
            const Vec3 &p0 = m.vertices[static_cast<size_t>(f[0])], &p1 = m.vertices[static_cast<size_t>(f[1])], &p2 = m.vertices[static_cast<size_t>(f[2])];
            const Vec3 e1 = p1 - p0, e2 = p2 - p0;
            const double l1 = e1.norm();
            const Vec3 xa = e1 / l1, normal = e1.cross(e2).normalized(), ya = normal.cross(xa);
            Eigen::Matrix2d P, U;
            P << l1, e2.dot(xa), 0, e2.dot(ya);
            const Complex d1 = (z[tp.corner_use[3 * t + 1]] - z[tp.corner_use[3 * t]]) * ls, d2 = (z[tp.corner_use[3 * t + 2]] - z[tp.corner_use[3 * t]]) * ls;
            U << d1.real(), d2.real(), d1.imag(), d2.imag();
            const Eigen::Matrix2d J = U * P.inverse();
            // Singular values of a 2x2 as (E +- F) / 2: E measures the conformal part, F the
            // anti-conformal part, so a near-conformal map keeps full precision (the textbook
            // sqrt(tr^2/4 - det^2) form loses half the digits exactly there).
            const double a = J(0, 0), b = J(0, 1), c = J(1, 0), d = J(1, 1);
            const double E = std::hypot(a + d, c - b), F = std::hypot(a - d, c + b);
            const double s1 = 0.5 * (E + F), s2 = 0.5 * std::abs(E - F);
            const double ang = s2 > 0 ? s1 / s2 : 1e300;
            const double ar = std::abs(std::log(std::max(ratio, 1e-300)));
            a2[t] = w * r * r;
            a3[t] = w * ar;
            wang[t] = w * ang;
            angle_max = std::max(angle_max, ang);
            area_max = std::max(area_max, ar);
          }
          block_angle_max[static_cast<size_t>(blk)] = angle_max;
          block_area_max[static_cast<size_t>(blk)] = area_max;
        }
      },
      1);
  for (size_t t = 0; t < nt; ++t) {
    q.score += a2[t];
    q.angle_mean += wang[t];
    q.area_mean += a3[t];
  }
  for (Index blk = 0; blk < blocks; ++blk) {
    q.angle_max = std::max(q.angle_max, block_angle_max[static_cast<size_t>(blk)]);
    q.area_max = std::max(q.area_max, block_area_max[static_cast<size_t>(blk)]);
  }
  if (wsum > 0) {
    q.score /= wsum;
    q.angle_mean /= wsum;
    q.area_mean /= wsum;
  }
  q.boundary_intersections = count_boundary_intersections(tp, z);
  if (q.flips) q.score -= 1;
  if (q.boundary_intersections) q.score -= 2;
  return q;
}

}  // namespace wefm
