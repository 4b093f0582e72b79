#include "wefm/core/meshing/node_optimisation.hpp"

#include <algorithm>
#include <cmath>

#include "wefm/core/meshing/mesh_quality.hpp"
#include "wefm/core/meshing/node_triangles.hpp"

namespace wefm::meshing {

namespace {

// Gradient of sum log lambda over node v's triangles [first, last) w.r.t. its 3D position, and in
// `mean_edge` the mean length of its edges over the triangles with area (0 for none).
Vec3 log_lambda_gradient(const std::vector<Vec3>& xyz, const std::vector<std::array<Index, 3>>& tris, const Index* first,
                         const Index* last, Index v, double& mean_edge) {
  const Vec3 x = xyz[static_cast<size_t>(v)];
  Vec3 g = Vec3::Zero();
  double edge = 0;
  int edges = 0;
  for (const Index* k = first; k != last; ++k) {
    const auto& T = tris[static_cast<size_t>(*k)];
    int i = 0;
    while (T[static_cast<size_t>(i)] != v) ++i;
    const Vec3& a = xyz[static_cast<size_t>(T[static_cast<size_t>((i + 1) % 3)])];
    const Vec3& b = xyz[static_cast<size_t>(T[static_cast<size_t>((i + 2) % 3)])];
    const Vec3 N = (a - x).cross(b - x);
    const double area2 = N.norm();
    const double S = (a - x).squaredNorm() + (b - x).squaredNorm() + (a - b).squaredNorm();
    if (!(area2 > 0) || !(S > 0)) continue;
    // d area / dx = (a - b) x N^ / 2, d S / dx = 2 (2x - a - b).
    g += (a - b).cross(N / area2) / area2 - 2.0 * (2.0 * x - a - b) / S;
    edge += (a - x).norm();
    ++edges;
  }
  mean_edge = edges ? edge / edges : 0.0;
  return g;
}

}  // namespace

// One function of about 100 lines: the gradient, the parabola step along it and the acceptance
// share the node's star cache and the pass's bookkeeping, which steps of their own would each take
// and hand back.
std::int64_t optimise_nodes(std::vector<P2>& uv, std::vector<Vec3>& xyz, const std::vector<std::array<Index, 3>>& tris, Index fixed,
                            const SurfaceMap& map, double floor) {
  const size_t n = uv.size();
  const NodeTriangles around = node_triangles(n, tris);
  const std::vector<Index>& start = around.start;
  const std::vector<Index>& items = around.items;
  struct Star {
    double sum, worst;
  };
  // Lambda and its log per triangle at the current nodes (lambda -1: inverted in UV or flat in 3D),
  // measured when first needed and forgotten when a node of the triangle moves.
  std::vector<double> lam(tris.size()), log_lam(tris.size());
  std::vector<char> known(tris.size(), 0);
  auto measure = [&](size_t t, double& l, double& lg) {
    const auto& T = tris[t];
    const size_t a = static_cast<size_t>(T[0]), b = static_cast<size_t>(T[1]), c = static_cast<size_t>(T[2]);
    l = -1, lg = 0;
    if (!(orient2d(uv[a], uv[b], uv[c]) > 0)) return;
    const double x = lo_lambda(xyz[a], xyz[b], xyz[c]);
    if (x > 0) l = x, lg = std::log(x);
  };
  // Sum of log lambda and worst lambda over the star of v; sum = -inf if a UV triangle inverts.
  // `cached`: the nodes are where the cache was measured. `reject(l)`: a lambda l that rejects the
  // position whatever the rest stops the count; the worst returned is then <= l.
  auto star = [&](Index v, bool cached, auto reject) {
    Star s{0.0, 1.0};
    for (Index k = start[static_cast<size_t>(v)]; k < start[static_cast<size_t>(v) + 1]; ++k) {
      const size_t t = static_cast<size_t>(items[static_cast<size_t>(k)]);
      double l, lg;
      if (!cached) {
        measure(t, l, lg);
      } else {
        if (!known[t]) measure(t, lam[t], log_lam[t]), known[t] = 1;
        l = lam[t], lg = log_lam[t];
      }
      if (!(l > 0)) return Star{-1e300, -1.0};
      s.sum += lg;
      s.worst = std::min(s.worst, l);
      if (reject(l)) return s;
    }
    return s;
  };
  auto never = [](double) { return false; };
  std::int64_t moves = 0;
  for (Index v = fixed; v < static_cast<Index>(n); ++v) {
    const size_t vi = static_cast<size_t>(v);
    if (start[vi] == start[vi + 1]) continue;
    const Star before = star(v, true, never);
    if (!(before.worst > 0)) continue;
    Eigen::Matrix<double, 3, 2> J;
    if (!map.jacobian(uv[vi], J)) continue;
    const Vec3 nrm = J.col(0).cross(J.col(1));
    if (!(nrm.norm() > 0)) continue;
    const Vec3 unit_n = nrm.normalized();
    const Eigen::Matrix<double, 2, 3> back = (J.transpose() * J).inverse() * J.transpose();
    const Vec3 x = xyz[vi];
    double edge = 0;
    Vec3 g = log_lambda_gradient(xyz, tris, items.data() + start[vi], items.data() + start[vi + 1], v, edge);
    g -= g.dot(unit_n) * unit_n;
    const double slope = g.norm();
    if (!(slope > 0) || !(edge > 0)) continue;
    const Vec3 dir = g / slope;
    const P2 p0 = uv[vi];
    const double lowest = std::min(before.worst, floor);
    Vec3 lifted, best_y;
    // `full`: the sum is needed even where the move is rejected. Otherwise a UV triangle that
    // inverts or a lambda below `lowest` rejects the step, and the step is not lifted or counted on.
    auto try_step = [&](double t, Star& out, bool full) {
      const P2 p = p0 + back * (t * dir);
      Vec3 y;
      if (!map.lift(p, y)) return false;
      lifted = y;
      uv[vi] = p, xyz[vi] = y;
      out = full ? star(v, false, never) : star(v, false, [lowest](double l) { return l < lowest; });
      uv[vi] = p0, xyz[vi] = x;
      return true;
    };
    // Parabola through f(0), its slope and f(t1): its top is the step, within half an edge.
    const double t1 = 0.05 * edge;
    Star s1;
    if (!try_step(t1, s1, true)) continue;
    double best_t = 0;
    Star best = before;
    auto consider = [&](double t, const Star& s) {
      if (s.sum > best.sum + 1e-12 && s.worst >= lowest) best = s, best_t = t, best_y = lifted;
    };
    consider(t1, s1);
    const double curv = 2 * (before.sum + slope * t1 - s1.sum) / (t1 * t1);
    if (curv > 0) {
      const double t = std::min(slope / curv, 0.5 * edge);
      Star s;
      if (std::fabs(t - t1) > 1e-3 * t1 && try_step(t, s, false)) consider(t, s);
    }
    if (best_t > 0) {
      uv[vi] = p0 + back * (best_t * dir), xyz[vi] = best_y;
      for (Index k = start[vi]; k < start[vi + 1]; ++k) known[static_cast<size_t>(items[static_cast<size_t>(k)])] = 0;
      ++moves;
    }
  }
  return moves;
}

}  // namespace wefm::meshing
