#include "wefm/core/meshing/surface_locator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace wefm::meshing {

void closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, double w[3]) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  auto set = [&](double x, double y, double z) { w[0] = x, w[1] = y, w[2] = z; };
  if (d1 <= 0 && d2 <= 0) return set(1, 0, 0);
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return set(0, 1, 0);
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return set(1 - v, v, 0);
  }
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return set(0, 0, 1);
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double v = d2 / (d2 - d6);
    return set(1 - v, 0, v);
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double v = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return set(0, 1 - v, v);
  }
  const double den = va + vb + vc;
  if (!(std::fabs(den) > 0)) return set(1, 0, 0);  // degenerate triangle: its first corner
  const double v = vb / den, x = vc / den;
  set(1 - v - x, v, x);
}

SurfaceLocator::SurfaceLocator(const TriMesh& mesh) : mesh_(mesh) {
  Vec3 hi = Vec3::Constant(-1e300);
  lo_ = Vec3::Constant(1e300);
  double edge = 0;
  for (const Vec3& v : mesh.vertices) lo_ = lo_.cwiseMin(v), hi = hi.cwiseMax(v);
  for (const Tri& t : mesh.triangles) edge += (mesh.vertices[static_cast<size_t>(t[1])] - mesh.vertices[static_cast<size_t>(t[0])]).norm();
  const size_t nt = std::max<size_t>(1, mesh.triangles.size());
  edge /= static_cast<double>(nt);
  diag_ = (hi - lo_).norm();
  centre_ = 0.5 * lo_ + 0.5 * hi;
  cell_ = std::max(2.0 * edge, 1e-12 * std::max(diag_, 1e-300));
  // Keep the dense grid near a few cells per triangle.
  // Counted in doubles first: a face whose mean edge is 1e-12 of its extent asks for 1e12 cells a
  // side, past int.
  for (;;) {
    double total = 1;
    for (int k = 0; k < 3; ++k) total *= std::floor((hi[k] - lo_[k]) / cell_) + 1;
    if (total <= 8.0 * static_cast<double>(nt) + 64) break;
    cell_ *= 1.5;
  }
  for (int k = 0; k < 3; ++k) n_[k] = static_cast<int>((hi[k] - lo_[k]) / cell_) + 1;
  const size_t cells = static_cast<size_t>(n_[0]) * static_cast<size_t>(n_[1]) * static_cast<size_t>(n_[2]);
  auto cell_of = [&](const Vec3& p, int k) { return std::clamp(static_cast<int>((p[k] - lo_[k]) / cell_), 0, n_[k] - 1); };
  auto box = [&](const Tri& t, int lo[3], int hi_[3]) {
    const Vec3 &a = mesh.vertices[static_cast<size_t>(t[0])], &b = mesh.vertices[static_cast<size_t>(t[1])], &c = mesh.vertices[static_cast<size_t>(t[2])];
    for (int k = 0; k < 3; ++k) {
      lo[k] = cell_of(a.cwiseMin(b).cwiseMin(c), k);
      hi_[k] = cell_of(a.cwiseMax(b).cwiseMax(c), k);
    }
  };
  std::vector<Index> count(cells + 1, 0);
  for (int pass = 0; pass < 2; ++pass) {
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
      int a[3], b[3];
      box(mesh.triangles[t], a, b);
      for (int z = a[2]; z <= b[2]; ++z)
        for (int y = a[1]; y <= b[1]; ++y)
          for (int x = a[0]; x <= b[0]; ++x) {
            const size_t id = (static_cast<size_t>(z) * static_cast<size_t>(n_[1]) + static_cast<size_t>(y)) * static_cast<size_t>(n_[0]) + static_cast<size_t>(x);
            if (pass == 0)
              count[id + 1]++;
            else
              items_[static_cast<size_t>(count[id]++)] = static_cast<Index>(t);
          }
    }
    if (pass == 0) {
      for (size_t k = 1; k < count.size(); ++k) count[k] += count[k - 1];
      start_ = count;
      items_.resize(static_cast<size_t>(count.back()));
    }
  }
}

SurfaceHit SurfaceLocator::closest(const Vec3& q) const {
  SurfaceHit hit;
  hit.distance = std::numeric_limits<double>::infinity();
  if (!q.allFinite() || mesh_.triangles.empty()) return hit;
  const Vec3 p = within_reach(q);
  int c[3];
  // Clamped as a double: a far point's quotient overflows an int.
  for (int k = 0; k < 3; ++k) c[k] = static_cast<int>(std::clamp(std::floor((p[k] - lo_[k]) / cell_), 0.0, static_cast<double>(n_[k] - 1)));
  double best = std::numeric_limits<double>::infinity();
  const int rmax = std::max({n_[0], n_[1], n_[2]});
  for (int r = 0; r <= rmax; ++r) {
    for (int z = std::max(0, c[2] - r); z <= std::min(n_[2] - 1, c[2] + r); ++z)
      for (int y = std::max(0, c[1] - r); y <= std::min(n_[1] - 1, c[1] + r); ++y)
        for (int x = std::max(0, c[0] - r); x <= std::min(n_[0] - 1, c[0] + r); ++x) {
          if (std::max({std::abs(x - c[0]), std::abs(y - c[1]), std::abs(z - c[2])}) != r) continue;
          const size_t id = (static_cast<size_t>(z) * static_cast<size_t>(n_[1]) + static_cast<size_t>(y)) * static_cast<size_t>(n_[0]) + static_cast<size_t>(x);
          for (Index k = start_[id]; k < start_[id + 1]; ++k) {
            const Tri& t = mesh_.triangles[static_cast<size_t>(items_[static_cast<size_t>(k)])];
            const Vec3 &a = mesh_.vertices[static_cast<size_t>(t[0])], &b = mesh_.vertices[static_cast<size_t>(t[1])], &cc = mesh_.vertices[static_cast<size_t>(t[2])];
            double w[3];
            closest_on_triangle(p, a, b, cc, w);
            const double d2 = (w[0] * a + w[1] * b + w[2] * cc - p).squaredNorm();
            if (d2 < best) {
              best = d2;
              hit.tri = items_[static_cast<size_t>(k)];
              std::copy(w, w + 3, hit.bary);
            }
          }
        }
    // Cells not yet searched lie beyond the sides of the searched block that are still inside the
    // grid; a point outside the grid is nearer to none of them than to those sides.
    double margin = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k) {
      if (c[k] - r > 0) margin = std::min(margin, p[k] - (lo_[k] + (c[k] - r) * cell_));
      if (c[k] + r < n_[k] - 1) margin = std::min(margin, (lo_[k] + (c[k] + r + 1) * cell_) - p[k]);
    }
    if (hit.tri >= 0 && std::sqrt(best) <= margin) break;
  }
  hit.distance = std::sqrt(best);
  if (hit.tri >= 0 && !(p == q)) {  // the distance to the point itself, not to its stand-in
    const Tri& t = mesh_.triangles[static_cast<size_t>(hit.tri)];
    const Vec3 x = hit.bary[0] * mesh_.vertices[static_cast<size_t>(t[0])] + hit.bary[1] * mesh_.vertices[static_cast<size_t>(t[1])] +
                   hit.bary[2] * mesh_.vertices[static_cast<size_t>(t[2])];
    const Vec3 d = 0.5 * x - 0.5 * q;
    hit.distance = 2 * std::hypot(d.x(), d.y(), d.z());
  }
  return hit;
}

Vec3 SurfaceLocator::within_reach(const Vec3& p) const {
  // Halved differences cannot overflow for finite operands.
  const Vec3 half = 0.5 * p - 0.5 * centre_;
  const double len = std::hypot(half.x(), half.y(), half.z());
  const double reach = kReach * std::max(diag_, 1e-300);
  if (!(2 * len > reach)) return p;
  return centre_ + half * (reach / len);
}

}  // namespace wefm::meshing
