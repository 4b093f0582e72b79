#include "wefm/core/meshing/uv_locator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace wefm::meshing {
namespace {

// Barycentric coordinates of p in (a, b, c); false for a degenerate triangle.
bool barycentric(const P2& p, const P2& a, const P2& b, const P2& c, double w[3]) {
  const double d = (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
  if (!(std::fabs(d) > 0)) return false;
  w[1] = ((p.x() - a.x()) * (c.y() - a.y()) - (p.y() - a.y()) * (c.x() - a.x())) / d;
  w[2] = ((b.x() - a.x()) * (p.y() - a.y()) - (b.y() - a.y()) * (p.x() - a.x())) / d;
  w[0] = 1.0 - w[1] - w[2];
  return true;
}

// Distance from p to segment ab and the parameter of the closest point. Computed on the vectors
// scaled to their largest component, so a domain or a point past 1e154 (whose squared lengths
// overflow) still gets a finite answer wherever the distance itself is finite.
double segment_distance(const P2& p, const P2& a, const P2& b, double& t) {
  const P2 ab = b - a, ap = p - a;
  const double m = std::max({std::fabs(ab.x()), std::fabs(ab.y()), std::fabs(ap.x()), std::fabs(ap.y())});
  if (!(m > 0) || !std::isfinite(m)) {
    t = 0;
    return std::hypot(ap.x(), ap.y());
  }
  const P2 u = ab / m, v = ap / m;
  const double l2 = u.squaredNorm();
  t = l2 > 0 ? std::clamp(v.dot(u) / l2, 0.0, 1.0) : 0.0;
  const P2 d = v - t * u;
  return m * std::hypot(d.x(), d.y());
}

}  // namespace

UvLocator::UvLocator(const TriMesh& mesh, const Topology& topo, const VectorXc& uv) : mesh_(mesh) {
  const size_t nt = mesh.triangles.size();
  uv_.resize(3 * nt);
  scale_.resize(nt);
  hi_ = P2(-1e300, -1e300);
  lo_ = P2(1e300, 1e300);
  for (size_t t = 0; t < nt; ++t) {
    for (int k = 0; k < 3; ++k) {
      const Complex z = uv[topo.corner_use[3 * t + static_cast<size_t>(k)]];
      uv_[3 * t + static_cast<size_t>(k)] = P2(z.real(), z.imag());
      lo_ = lo_.cwiseMin(uv_[3 * t + static_cast<size_t>(k)]);
      hi_ = hi_.cwiseMax(uv_[3 * t + static_cast<size_t>(k)]);
    }
    const Tri& tr = mesh.triangles[t];
    const double a3 = 0.5 * (mesh.vertices[static_cast<size_t>(tr[1])] - mesh.vertices[static_cast<size_t>(tr[0])])
                                .cross(mesh.vertices[static_cast<size_t>(tr[2])] - mesh.vertices[static_cast<size_t>(tr[0])]).norm();
    const P2 e1 = uv_[3 * t + 1] - uv_[3 * t], e2 = uv_[3 * t + 2] - uv_[3 * t];
    const double a2 = 0.5 * std::fabs(e1.x() * e2.y() - e1.y() * e2.x());
    scale_[t] = a2 > 0 ? std::sqrt(a3 / a2) : 0.0;
  }
  reach_ = kReach * std::max((hi_ - lo_).norm(), 1e-300);
  const P2 ext = (hi_ - lo_).cwiseMax(P2(1e-300, 1e-300));
  const double cells = std::max<double>(1.0, static_cast<double>(nt));
  const double c = std::sqrt(ext.x() * ext.y() / cells);
  // Clamped as doubles: a domain of (almost) no width has quotients past any int.
  double fx = std::clamp(std::floor(ext.x() / std::max(c, 1e-300)) + 1, 1.0, 4096.0);
  double fy = std::clamp(std::floor(ext.y() / std::max(c, 1e-300)) + 1, 1.0, 4096.0);
  // A few cells per triangle at most: a domain of almost no width in one direction would otherwise
  // get a grid of millions of empty cells, built and searched for every point.
  const double budget = 4 * cells + 64;
  if (fx * fy > budget) {
    const double k = std::sqrt(budget / (fx * fy));
    fx = std::max(1.0, std::floor(fx * k));
    fy = std::max(1.0, std::floor(fy * k));
    if (fx * fy > budget) (fx > fy ? fx : fy) = std::max(1.0, std::floor(budget / std::min(fx, fy)));
  }
  nx_ = static_cast<int>(fx);
  ny_ = static_cast<int>(fy);
  cell_ = P2(ext.x() / nx_, ext.y() / ny_);
  std::vector<Index> count(static_cast<size_t>(nx_ * ny_) + 1, 0);
  auto range = [&](size_t t, int& i0, int& i1, int& j0, int& j1) {
    P2 a = uv_[3 * t].cwiseMin(uv_[3 * t + 1]).cwiseMin(uv_[3 * t + 2]);
    P2 b = uv_[3 * t].cwiseMax(uv_[3 * t + 1]).cwiseMax(uv_[3 * t + 2]);
    i0 = std::clamp(static_cast<int>((a.x() - lo_.x()) / cell_.x()), 0, nx_ - 1);
    i1 = std::clamp(static_cast<int>((b.x() - lo_.x()) / cell_.x()), 0, nx_ - 1);
    j0 = std::clamp(static_cast<int>((a.y() - lo_.y()) / cell_.y()), 0, ny_ - 1);
    j1 = std::clamp(static_cast<int>((b.y() - lo_.y()) / cell_.y()), 0, ny_ - 1);
  };
  for (size_t t = 0; t < nt; ++t) {
    int i0, i1, j0, j1;
    range(t, i0, i1, j0, j1);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) count[static_cast<size_t>(j * nx_ + i) + 1]++;
  }
  for (size_t k = 1; k < count.size(); ++k) count[k] += count[k - 1];
  start_ = count;
  items_.resize(static_cast<size_t>(count.back()));
  for (size_t t = 0; t < nt; ++t) {
    int i0, i1, j0, j1;
    range(t, i0, i1, j0, j1);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) items_[static_cast<size_t>(count[static_cast<size_t>(j * nx_ + i)]++)] = static_cast<Index>(t);
  }
}

UvHit UvLocator::locate(const P2& q) const {
  UvHit hit;
  if (!q.allFinite() || start_.empty()) return hit;
  const P2 p = within_reach(q);
  // The cell index is clamped as a double: a far point's quotient overflows an int.
  const int ci = static_cast<int>(std::clamp(std::floor((p.x() - lo_.x()) / cell_.x()), 0.0, static_cast<double>(nx_ - 1)));
  const int cj = static_cast<int>(std::clamp(std::floor((p.y() - lo_.y()) / cell_.y()), 0.0, static_cast<double>(ny_ - 1)));
  // Inside: the triangle whose smallest barycentric coordinate is largest, so a point on a shared
  // edge picks one triangle deterministically and round-off never leaves it outside.
  double best_min = -1e-12;
  for (Index k = start_[static_cast<size_t>(cj * nx_ + ci)]; k < start_[static_cast<size_t>(cj * nx_ + ci) + 1]; ++k) {
    const Index t = items_[static_cast<size_t>(k)];
    double w[3];
    if (!barycentric(p, corner(t, 0), corner(t, 1), corner(t, 2), w)) continue;
    const double m = std::min({w[0], w[1], w[2]});
    if (m >= best_min) {
      best_min = m;
      hit.tri = t;
      std::copy(w, w + 3, hit.bary);
      hit.inside = true;
      if (m > 0) break;
    }
  }
  if (hit.inside) return hit;
  nearest_on_boundary(p, ci, cj, hit);
  return hit;
}

P2 UvLocator::within_reach(const P2& p) const {
  // Halved differences cannot overflow for finite operands.
  const P2 centre = 0.5 * lo_ + 0.5 * hi_;
  const P2 half = 0.5 * p - 0.5 * centre;
  // |half| <= |x| + |y|: a point well within reach by that bound needs no exact length.
  if (2 * (std::fabs(half.x()) + std::fabs(half.y())) <= reach_ * (1 - 1e-9)) return p;
  const double len = std::hypot(half.x(), half.y());
  if (!(2 * len > reach_)) return p;
  return centre + half * (reach_ / len);
}

void UvLocator::nearest_on_boundary(const P2& p, int ci, int cj, UvHit& hit) const {
  // Nearest point of the domain, searching growing rings of cells.
  double best = std::numeric_limits<double>::infinity();
  const int rmax = std::max(nx_, ny_);
  auto visit = [&](int i, int j) {
    for (Index k = start_[static_cast<size_t>(j * nx_ + i)]; k < start_[static_cast<size_t>(j * nx_ + i) + 1]; ++k) {
      const Index t = items_[static_cast<size_t>(k)];
      for (int e = 0; e < 3; ++e) {
        double s;
        const double d = segment_distance(p, corner(t, e), corner(t, (e + 1) % 3), s);
        if (d < best || hit.tri < 0) {  // the first candidate even at an infinite distance
          best = d;
          hit.tri = t;
          hit.bary[e] = 1 - s;
          hit.bary[(e + 1) % 3] = s;
          hit.bary[(e + 2) % 3] = 0;
        }
      }
    }
  };
  for (int r = 0; r <= rmax; ++r) {
    const int i0 = std::max(0, ci - r), i1 = std::min(nx_ - 1, ci + r);
    const int j0 = std::max(0, cj - r), j1 = std::min(ny_ - 1, cj + r);
    for (int j = j0; j <= j1; ++j) {
      if (j == cj - r || j == cj + r) {
        for (int i = i0; i <= i1; ++i) visit(i, j);
      } else {
        if (ci - r >= 0) visit(ci - r, j);
        if (ci + r < nx_) visit(ci + r, j);
      }
    }
    // Cells not yet searched lie beyond the sides of the searched block that are still inside the
    // grid; a point outside the grid is nearer to none of them than to those sides.
    double margin = std::numeric_limits<double>::infinity();
    if (ci - r > 0) margin = std::min(margin, p.x() - (lo_.x() + (ci - r) * cell_.x()));
    if (ci + r < nx_ - 1) margin = std::min(margin, (lo_.x() + (ci + r + 1) * cell_.x()) - p.x());
    if (cj - r > 0) margin = std::min(margin, p.y() - (lo_.y() + (cj - r) * cell_.y()));
    if (cj + r < ny_ - 1) margin = std::min(margin, (lo_.y() + (cj + r + 1) * cell_.y()) - p.y());
    if (hit.tri >= 0 && best <= margin) break;
  }
}

Vec3 UvLocator::to_3d(const UvHit& hit) const {
  if (hit.tri < 0) return Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
  const Tri& t = mesh_.triangles[static_cast<size_t>(hit.tri)];
  return hit.bary[0] * mesh_.vertices[static_cast<size_t>(t[0])] + hit.bary[1] * mesh_.vertices[static_cast<size_t>(t[1])] +
         hit.bary[2] * mesh_.vertices[static_cast<size_t>(t[2])];
}

}  // namespace wefm::meshing
