#include "wefm/core/meshing/frontal.hpp"

#include <algorithm>
#include <cmath>
#include <queue>

namespace wefm::meshing {
namespace {

constexpr double kSqrt3 = 1.7320508075688772;
// Rescalings of the step when the apex lifted to 3D misses its height (see below).
constexpr int kCorrections = 2;

struct Entry {
  double ratio;
  Index slot;
  std::uint32_t gen;
  // Largest ratio first; ties by slot so the order never depends on the heap's internals.
  bool operator<(const Entry& o) const { return ratio != o.ratio ? ratio < o.ratio : slot > o.slot; }
};

struct SlotState {
  std::uint32_t gen = 0;
  bool known = false;
  bool dead_end = false;  // no node could be placed for it: counts as accepted
  double ratio = 0;
};

// Distance from the midpoint of a front edge (3D half-length `half`) along its bisector to the
// new node: the apex of the triangle on the edge with circumradius max(target, half), but not
// past the circumcentre of the triangle being replaced (at signed distance q on the bisector,
// circumradius r) when that lies in front of the edge.
double front_distance(double half, double target_radius, double q, double r) {
  double rho = std::max(target_radius, half);
  if (q > half) rho = std::min(rho, (half * half + q * q) / (2 * q));
  const double d = rho + std::sqrt(std::max(0.0, rho * rho - half * half));
  return std::min(d, q >= half ? q : 0.5 * (q + r));
}

}  // namespace

double size_ratio(const Vec3& a, const Vec3& b, const Vec3& c, double size) {
  const double la = (b - c).norm(), lb = (c - a).norm(), lc = (a - b).norm();
  const double area2 = (b - a).cross(c - a).norm();
  if (!(area2 > 0) || !(size > 0)) return 1e300;
  return kSqrt3 * la * lb * lc / (2 * area2) / size;
}

namespace {

// The new node on the front edge (a, b) of a triangle with apex c: along the edge's bisector in
// UV at the height front_distance asks for, with the step rescaled where the UV scale changes over
// it. False when it cannot be placed (a degenerate edge or triangle, a point off the domain).
// `h_here`: the size at the edge's midpoint.
bool front_apex(const Triangulation& tr, const std::vector<Vec3>& xyz, const SurfaceMap& map, const SizeField& size, Index a, Index b,
                Index c, P2& p, Vec3& x, double& h_here) {
  const Vec3 &xa = xyz[static_cast<size_t>(a)], &xb = xyz[static_cast<size_t>(b)], &xc = xyz[static_cast<size_t>(c)];
  // The bisector in UV: the direction M-orthogonal to the edge, M = J^T J the first fundamental
  // form, with unit M-length, so a step d along it is (to first order) d in 3D.
  const P2 ua = tr.node(a), ub = tr.node(b);
  const P2 m = 0.5 * (ua + ub);
  Eigen::Matrix<double, 3, 2> J;
  if (!map.jacobian(m, J)) return false;
  const Eigen::Matrix2d M = J.transpose() * J;
  const P2 edge = ub - ua;
  P2 n = M.inverse() * P2(-edge.y(), edge.x());
  const double nn = n.dot(M * n);
  if (!(nn > 0) || !std::isfinite(nn)) return false;
  n /= std::sqrt(nn);
  // The replaced triangle's circumcentre in 3D, as a signed distance along the bisector.
  const Vec3 u = xb - xa, w = xc - xa, uw = u.cross(w);
  const double uw2 = uw.squaredNorm();
  if (!(uw2 > 0)) return false;
  const Vec3 cc = xa + (w.squaredNorm() * uw.cross(u) + u.squaredNorm() * w.cross(uw)) / (2 * uw2);
  const Vec3 m3 = 0.5 * (xa + xb);
  const double q = (cc - m3).dot(uw.cross(u).normalized());
  h_here = size.at(m3);
  const double half = 0.5 * u.norm();
  const double d = front_distance(half, h_here / kSqrt3, q, (cc - xa).norm());
  p = m + d * n;
  bool lifted = d > 0 && map.lift(p, x);
  // The metric is the one at the edge midpoint; where the UV scale changes over the step (a
  // sphere's domain), rescale the step until the apex stands at the intended 3D height.
  double step = d;
  for (int it = 0; it < kCorrections && lifted; ++it) {
    const double side = 0.5 * ((x - xa).norm() + (x - xb).norm());
    const double height = std::sqrt(std::max(0.0, side * side - half * half));
    if (!(height > 0) || std::fabs(height - d) < 0.02 * d) break;
    step *= std::clamp(d / height, 0.5, 2.0);
    p = m + step * n;
    lifted = map.lift(p, x);
  }
  return lifted;
}

}  // namespace

std::int64_t frontal_refine(Triangulation& tr, std::vector<Vec3>& xyz, std::vector<double>& node_size, const SurfaceMap& map,
                            const SizeField& size, const FrontalSettings& set, const std::function<void()>& tick) {
  std::vector<SlotState> state;
  auto info = [&](Index t) -> SlotState& {
    if (state.size() <= static_cast<size_t>(t)) state.resize(static_cast<size_t>(t) + 1);
    SlotState& s = state[static_cast<size_t>(t)];
    if (!s.known || s.gen != tr.generation(t)) {
      s = SlotState{};
      s.gen = tr.generation(t), s.known = true;
      const size_t a = static_cast<size_t>(tr.corner(t, 0)), b = static_cast<size_t>(tr.corner(t, 1)), c = static_cast<size_t>(tr.corner(t, 2));
      s.ratio = size_ratio(xyz[a], xyz[b], xyz[c], (node_size[a] + node_size[b] + node_size[c]) / 3);
    }
    return s;
  };
  auto accepted = [&](Index t) {
    const SlotState& s = info(t);
    return s.dead_end || s.ratio < set.accept_ratio;
  };
  std::priority_queue<Entry> heap;
  auto push = [&](Index t) {
    if (t < 0 || !tr.live(t) || !tr.inside(t) || accepted(t)) return;
    heap.push({info(t).ratio, t, tr.generation(t)});
  };
  // The front edge of t: one bordering the boundary or an accepted triangle, the one whose length
  // is nearest its target size (the new triangle then comes out nearest equilateral); -1 if none.
  auto front_edge = [&](Index t) {
    int best = -1;
    double best_score = 1e300;
    for (int i = 0; i < 3; ++i) {
      const Index s = tr.neighbour(t, i);
      if (!(tr.constrained(t, i) || s < 0 || !tr.inside(s) || accepted(s))) continue;
      const size_t a = static_cast<size_t>(tr.corner(t, (i + 1) % 3)), b = static_cast<size_t>(tr.corner(t, (i + 2) % 3));
      const double len = (xyz[b] - xyz[a]).norm();
      const double score = std::fabs(std::log(std::max(len, 1e-300) / (0.5 * (node_size[a] + node_size[b]))));
      if (score < best_score) best_score = score, best = i;
    }
    return best;
  };
  for (Index t = 0; t < tr.slot_count(); ++t) push(t);

  std::int64_t inserted = 0;
  const std::int64_t cap = set.max_nodes > 0 ? set.max_nodes : (std::int64_t(1) << 40);
  while (!heap.empty() && tr.node_count() < cap) {
    const Entry e = heap.top();
    heap.pop();
    const Index t = e.slot;
    if (!tr.live(t) || tr.generation(t) != e.gen || accepted(t)) continue;
    const int i = front_edge(t);
    if (i < 0) continue;  // queued again when a neighbour is accepted
    const Index a = tr.corner(t, (i + 1) % 3), b = tr.corner(t, (i + 2) % 3), c = tr.corner(t, i);
    // Given up triangles count as accepted, so the front moves past them; what stays too large
    // is left to circumcentre refinement.
    auto give_up = [&] {
      info(t).dead_end = true;
      for (int k = 0; k < 3; ++k) push(tr.neighbour(t, k));
    };
    P2 p;
    Vec3 x;
    double h_here = 0;
    if (!front_apex(tr, xyz, map, size, a, b, c, p, x, h_here)) {
      give_up();
      continue;
    }
    // A node that would come closer than this to an existing one (fronts meeting) is not placed.
    const double clearance = 0.4 * h_here;
    const std::function<bool(Index)> near_ok = [&](Index v) { return (xyz[static_cast<size_t>(v)] - x).norm() >= clearance; };
    std::array<Index, 2> enc{{-1, -1}};
    const Index v = tr.insert(p, t, &enc, &near_ok);
    if (v < 0) {
      give_up();
      continue;
    }
    if (xyz.size() <= static_cast<size_t>(v)) xyz.resize(static_cast<size_t>(v) + 1), node_size.resize(static_cast<size_t>(v) + 1);
    xyz[static_cast<size_t>(v)] = x;
    node_size[static_cast<size_t>(v)] = size.at(x);
    ++inserted;
    tick();
    for (Index s : tr.triangles_around(v)) {
      push(s);
      int k = 0;
      while (tr.corner(s, k) != v) ++k;
      push(tr.neighbour(s, k));
    }
  }
  return inserted;
}

}  // namespace wefm::meshing
