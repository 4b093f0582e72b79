#include "wefm/core/meshing/recombine.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

#include "wefm/common/element_corners.hpp"
#include "wefm/core/meshing/hard_edges.hpp"
#include "wefm/core/meshing/mesh_quality.hpp"

namespace wefm::meshing {

namespace {

// Past this many triangles reached, the search for an alternating path from one unmatched triangle
// gives up: a path that long would shuffle quads across the face for one more quad, and the search
// over every leftover triangle must stay near linear in the mesh.
constexpr size_t kSearchLimit = 400;

double cross2(const P2& o, const P2& a, const P2& b) { return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x(); }

// A quad a, b, c, d counter-clockwise in UV with every corner turning left (strictly convex).
bool convex_in_uv(const std::vector<P2>& uv, const std::array<Index, 4>& q) {
  for (int k = 0; k < 4; ++k)
    if (!(cross2(uv[static_cast<size_t>(q[k])], uv[static_cast<size_t>(q[(k + 1) % 4])], uv[static_cast<size_t>(q[(k + 3) % 4])]) > 0))
      return false;
  return true;
}

// A pair of triangles that may become a quad, and how good the quad would be.
struct Candidate {
  Index t1, t2;
  std::array<Index, 4> quad;
  double quality;
};

// Candidate quads over each edge inside the face but the hard ones, with the triangles' dual graph
// (per triangle, its candidates by index).
std::vector<Candidate> candidates(const DomainMesh& m, double min_quality, std::vector<std::vector<size_t>>& of_triangle) {
  const size_t nt = m.elements.size() / 3;
  std::unordered_map<std::uint64_t, std::pair<Index, int>> first;  // edge -> triangle, its corner before the edge
  first.reserve(3 * nt);
  std::vector<Candidate> out;
  of_triangle.assign(nt, {});
  const Index* T = m.elements.data();
  const HardEdges hard(m.hard_edges);
  for (size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) {
      const Index a = T[3 * t + static_cast<size_t>(k)], b = T[3 * t + static_cast<size_t>((k + 1) % 3)];
      const auto [it, fresh] = first.emplace(edge_key(a, b), std::pair<Index, int>{static_cast<Index>(t), k});
      if (fresh) continue;
      // t1 = (a1, b1, c) holds the edge a1 -> b1, t2 = (b1, a1, d) the other way: the quad is
      // a1, d, b1, c counter-clockwise.
      const Index t1 = it->second.first;
      const int k1 = it->second.second;
      const Index a1 = T[3 * static_cast<size_t>(t1) + static_cast<size_t>(k1)];
      const Index b1 = T[3 * static_cast<size_t>(t1) + static_cast<size_t>((k1 + 1) % 3)];
      const Index c = T[3 * static_cast<size_t>(t1) + static_cast<size_t>((k1 + 2) % 3)];
      const Index d = T[3 * t + static_cast<size_t>((k + 2) % 3)];
      if (a1 != b || b1 != a || hard.has(a, b)) continue;  // not one orientation, or an edge to keep: no quad across it
      const std::array<Index, 4> q{a1, d, b1, c};
      if (!convex_in_uv(m.uv, q)) continue;
      const double quality = scaled_jacobian(m.xyz[static_cast<size_t>(q[0])], m.xyz[static_cast<size_t>(q[1])],
                                             m.xyz[static_cast<size_t>(q[2])], m.xyz[static_cast<size_t>(q[3])]);
      if (!(quality >= min_quality)) continue;
      of_triangle[static_cast<size_t>(t1)].push_back(out.size());
      of_triangle[t].push_back(out.size());
      out.push_back({t1, static_cast<Index>(t), q, quality});
    }
  return out;
}

Index other(const Candidate& c, Index t) { return c.t1 == t ? c.t2 : c.t1; }

// From an unmatched triangle, a shortest path that alternates free and matched pairs and ends at
// another unmatched triangle; flipping it makes one more quad. Triangles reached at odd distance
// are not searched from again, so a path through an odd cycle may be missed: the leftover
// triangles are then what a maximum matching might have avoided.
bool augment(Index start, const std::vector<Candidate>& cand, const std::vector<std::vector<size_t>>& of_triangle,
             std::vector<std::int64_t>& mate, std::vector<std::uint32_t>& seen, std::uint32_t stamp) {
  struct Step {
    Index outer;         // a triangle searched from
    std::int64_t via;    // the candidate that reached its partner, or -1 at the start
    std::int64_t back;   // the step before
  };
  std::vector<Step> steps{{start, -1, -1}};
  seen[static_cast<size_t>(start)] = stamp;
  for (size_t head = 0; head < steps.size() && steps.size() < kSearchLimit; ++head) {
    const Index x = steps[head].outer;
    for (size_t ci : of_triangle[static_cast<size_t>(x)]) {
      if (mate[static_cast<size_t>(x)] == static_cast<std::int64_t>(ci)) continue;
      const Index y = other(cand[ci], x);
      if (seen[static_cast<size_t>(y)] == stamp) continue;
      seen[static_cast<size_t>(y)] = stamp;
      if (mate[static_cast<size_t>(y)] < 0) {
        // Flip back to the start: x takes y, and each outer triangle's old partner takes the
        // triangle the search came from.
        std::int64_t s = static_cast<std::int64_t>(head);
        std::int64_t take = static_cast<std::int64_t>(ci);
        while (s >= 0) {
          const Candidate& c = cand[static_cast<size_t>(take)];
          mate[static_cast<size_t>(c.t1)] = take, mate[static_cast<size_t>(c.t2)] = take;
          take = steps[static_cast<size_t>(s)].via;
          s = steps[static_cast<size_t>(s)].back;
        }
        return true;
      }
      const Index z = other(cand[static_cast<size_t>(mate[static_cast<size_t>(y)])], y);
      if (seen[static_cast<size_t>(z)] == stamp) continue;
      seen[static_cast<size_t>(z)] = stamp;
      steps.push_back({z, static_cast<std::int64_t>(ci), static_cast<std::int64_t>(head)});
    }
  }
  return false;
}

// The quads' bar (issue 32: scaled Jacobian 0.3). A move is judged by the worst element round the
// node, which may be a triangle under it (Lo lambda 0.19 beside a sliver): in a quad-dominant mesh,
// whose quads recombine made at or above the bar, a move keeps them there all the same.
constexpr double kQuadBar = 0.3;

bool is_quad(const DomainMesh& m, size_t e) { return m.elements[4 * e + 3] >= 0; }

// The quality of element e in 3D: a quad's scaled Jacobian, a triangle's Lo lambda (both 1 at best,
// 0 or less when degenerate or folded); -1 when it is not convex (a quad) or inverted (a triangle)
// in UV, where it must stay a valid element of the domain.
double element_quality(const DomainMesh& m, size_t e) {
  const Index* v = &m.elements[4 * e];
  auto X = [&](int k) -> const Vec3& { return m.xyz[static_cast<size_t>(v[k])]; };
  if (v[3] < 0) {
    if (!(cross2(m.uv[static_cast<size_t>(v[0])], m.uv[static_cast<size_t>(v[1])], m.uv[static_cast<size_t>(v[2])]) > 0)) return -1;
    return lo_lambda(X(0), X(1), X(2));
  }
  if (!convex_in_uv(m.uv, {v[0], v[1], v[2], v[3]})) return -1;
  return scaled_jacobian(X(0), X(1), X(2), X(3));
}

// The worst quality over elements `es`.
double worst_of(const DomainMesh& m, const std::vector<size_t>& es) {
  double w = 2;
  for (size_t e : es) w = std::min(w, element_quality(m, e));
  return w;
}

// The worst quality over all of m's elements.
double worst_of(const DomainMesh& m) {
  double w = 2;
  for (size_t e = 0; e < m.elements.size() / 4; ++e) w = std::min(w, element_quality(m, e));
  return w;
}

// The scaled Jacobian the quads around a folded element keep while a compass search unfolds it.
constexpr double kUnfoldedFloor = 1e-3;

// Compass moves of node i: 8 directions from the best position so far, the step halved `levels` - 1
// times; a position is kept where `score` (of the mesh with the node there) beats the best so far,
// a score of -inf refusing it. The node ends at the best position.
template <class Score>
void compass(DomainMesh& m, const SurfaceMap& map, size_t i, double step, int levels, double best, const Score& score) {
  P2 best_uv = m.uv[i];
  Vec3 best_xyz = m.xyz[i], best_normal = m.normal[i];
  for (int level = 0; level < levels; ++level, step *= 0.5)
    for (int dir = 0; dir < 8; ++dir) {
      m.uv[i] = best_uv + step * P2(std::cos(dir * 0.25 * kPi), std::sin(dir * 0.25 * kPi));
      Vec3 x, nrm;
      if (!map.lift(m.uv[i], x, &nrm)) continue;
      m.xyz[i] = x, m.normal[i] = nrm;
      const double s = score();
      if (s > best + 1e-12) best = s, best_uv = m.uv[i], best_xyz = x, best_normal = nrm;
    }
  m.uv[i] = best_uv, m.xyz[i] = best_xyz, m.normal[i] = best_normal;
}

// Compass search on the worst element around node i (the step halved 6 times from `step`): where
// a Laplacian move cannot lift a poor element (a quad split from a sliver, or folded next to a
// chord's midpoint) a move towards no particular point often can. Keeps the best position at which
// no quad that had a scaled Jacobian of `floor` falls below it (a triangle lifted at a quad's
// expense would break the quads' bar).
void compass_search(DomainMesh& m, const SurfaceMap& map, size_t i, const std::vector<size_t>& around, double step, double floor) {
  const double now = worst_of(m, around);
  // A folded element (or one not convex in UV) is worse than any valid one: while one is around, the
  // quads at the floor may go below it, as long as none of them folds.
  const double keep = now > 0 ? floor : kUnfoldedFloor;
  std::vector<size_t> held;  // the quads at or above `keep`
  for (size_t e : around)
    if (is_quad(m, e) && element_quality(m, e) >= keep) held.push_back(e);
  compass(m, map, i, step, 6, now, [&] { return worst_of(m, held) < keep ? -HUGE_VAL : worst_of(m, around); });
}

// The elements round a node as a move sees them: the worst quality, the sum of f(quality), and
// whether every quad that was at the quads' bar before the move still is.
struct Star {
  double worst = 2, sum = 0;
  bool held = true;
};

// Measures the elements `es` round a node. On the first call for a node `at_bar` is empty and is
// filled (with `keep_quads`: the quads at or above kQuadBar, else none); later calls check them.
template <class F>
Star measure_star(const DomainMesh& m, const std::vector<size_t>& es, std::vector<char>& at_bar, bool keep_quads, const F& f) {
  const bool first = at_bar.empty();
  if (first) at_bar.assign(es.size(), 0);
  Star s;
  for (size_t k = 0; k < es.size(); ++k) {
    const double q = element_quality(m, es[k]);
    s.worst = std::min(s.worst, q), s.sum += f(q);
    if (first) at_bar[k] = keep_quads && is_quad(m, es[k]) && q >= kQuadBar;
    s.held = s.held && !(at_bar[k] && q < kQuadBar);
  }
  return s;
}

double log_quality(double q) { return std::log(std::max(q, 1e-12)); }

// Compass search on the sum of log qualities around node i (the step halved twice from `step`),
// keeping the worst element around it no worse: the geometric mean rewards squaring every quad a
// little over lifting one. Skips a node beside a folded element (compass_search's work).
void raise_mean(DomainMesh& m, const SurfaceMap& map, size_t i, const std::vector<size_t>& around, double step) {
  std::vector<char> at_bar;
  const Star now = measure_star(m, around, at_bar, true, log_quality);
  if (!(now.worst > 0)) return;
  compass(m, map, i, step, 3, now.sum, [&] {
    const Star s = measure_star(m, around, at_bar, true, log_quality);
    return s.worst >= now.worst && s.held ? s.sum : -HUGE_VAL;
  });
}

// Passes of raise_mean after the Laplacian ones (more gain little: docs/PERFORMANCE.md), and its
// first step as a fraction of the mean distance to the node's neighbours.
constexpr int kMeanPasses = 2;
constexpr double kMeanStep = 0.1;

// Nodes whose worst element stays below this after the Laplacian move get a compass search: the
// quads' bar, which the search then keeps the quads at.
constexpr double kSearchBelow = kQuadBar;
// Rounds of compass search over the nodes of folded elements and their neighbours, after the passes.
constexpr int kUnfoldRounds = 8;

// Gauss-Newton steps towards the UV point whose lift is nearest `target`: a split's new node at
// its UV midpoint or centre lifts far from the 3D midpoint or centre where the flattening stretches
// unevenly across the element (a face's pinch, sliver facets of the tessellation), and the quads
// split there fold. On the segment a + t (b - a) for an edge's middle (t kept in [1/4, 3/4]);
// anywhere for a centre, whose quads the caller checks. Each returns its start (the UV middle) when
// no step brings the lift nearer.
constexpr int kNearestSteps = 4;

double distance_of_lift(const SurfaceMap& map, const P2& p, const Vec3& target) {
  Vec3 x;
  return map.lift(p, x) ? (x - target).norm() : HUGE_VAL;
}

P2 nearest_on_segment(const SurfaceMap& map, const P2& a, const P2& b, const Vec3& target) {
  const P2 start = 0.5 * (a + b);
  double t = 0.5;
  for (int k = 0; k < kNearestSteps; ++k) {
    const P2 p = a + t * (b - a);
    Eigen::Matrix<double, 3, 2> J;
    Vec3 x;
    if (!map.lift(p, x) || !map.jacobian(p, J)) break;
    const Vec3 g = J * (b - a);
    const double gg = g.squaredNorm();
    if (!(gg > 0)) break;
    t = std::clamp(t + g.dot(target - x) / gg, 0.25, 0.75);
  }
  const P2 p = a + t * (b - a);
  return distance_of_lift(map, p, target) < distance_of_lift(map, start, target) ? p : start;
}

P2 nearest_point(const SurfaceMap& map, const P2& start, const Vec3& target, double reach) {
  P2 p = start;
  for (int k = 0; k < kNearestSteps; ++k) {
    Eigen::Matrix<double, 3, 2> J;
    Vec3 x;
    if (!map.lift(p, x) || !map.jacobian(p, J)) break;
    const Eigen::Matrix2d JtJ = J.transpose() * J;
    if (!(std::fabs(JtJ.determinant()) > 0)) break;
    P2 d = JtJ.ldlt().solve(J.transpose() * (target - x));
    if (!d.allFinite()) break;
    if (d.norm() > reach) d *= reach / d.norm();
    p += d;
  }
  return distance_of_lift(map, p, target) < distance_of_lift(map, start, target) ? p : start;
}

}  // namespace

void smooth_quads(DomainMesh& m, const SurfaceMap& map, int passes, bool for_mean) {
  if (m.nodes_per_element != 4) return;
  const size_t ne = m.elements.size() / 4, n = m.uv.size();
  std::vector<std::vector<size_t>> around(n);
  std::vector<std::vector<Index>> neighbours(n);
  for (size_t e = 0; e < ne; ++e) {
    const int c = static_cast<int>(wefm_common::element_corners(&m.elements[4 * e], 4));
    for (int k = 0; k < c; ++k) {
      const auto a = static_cast<size_t>(m.elements[4 * e + static_cast<size_t>(k)]);
      around[a].push_back(e);
      neighbours[a].push_back(m.elements[4 * e + static_cast<size_t>((k + 1) % c)]);
      neighbours[a].push_back(m.elements[4 * e + static_cast<size_t>((k + c - 1) % c)]);
    }
  }
  for (auto& nb : neighbours) {
    std::sort(nb.begin(), nb.end());
    nb.erase(std::unique(nb.begin(), nb.end()), nb.end());
  }
  const size_t first_free = static_cast<size_t>(std::max<Index>(m.boundary_nodes, 0));  // boundary nodes stay
  auto search = [&](size_t i) {
    double reach = 0;
    for (Index j : neighbours[i]) reach += (m.uv[static_cast<size_t>(j)] - m.uv[i]).norm();
    compass_search(m, map, i, around[i], 0.25 * reach / static_cast<double>(neighbours[i].size()), kSearchBelow);
  };
  auto identity = [](double q) { return q; };
  std::vector<char> at_bar;  // per element round the node: a quad a move keeps at the bar
  for (int pass = 0; pass < passes; ++pass) {
    for (size_t i = first_free; i < n; ++i) {
      if (neighbours[i].empty()) continue;
      at_bar.clear();
      const Star now = measure_star(m, around[i], at_bar, for_mean, identity);
      P2 target = P2::Zero();
      for (Index j : neighbours[i]) target += m.uv[static_cast<size_t>(j)];
      target /= static_cast<double>(neighbours[i].size());
      const P2 uv0 = m.uv[i];
      const Vec3 xyz0 = m.xyz[i], normal0 = m.normal[i];
      // The whole step, else half of it: kept only where the worst element around the node is no
      // worse and the elements are better on the whole.
      bool kept = false;
      for (double t : {1.0, 0.5}) {
        m.uv[i] = uv0 + t * (target - uv0);
        Vec3 x, nrm;
        if (!map.lift(m.uv[i], x, &nrm)) continue;
        m.xyz[i] = x, m.normal[i] = nrm;
        const Star s = measure_star(m, around[i], at_bar, for_mean, identity);
        if (s.worst >= now.worst && s.sum > now.sum && s.held) {
          kept = true;
          break;
        }
      }
      if (!kept) m.uv[i] = uv0, m.xyz[i] = xyz0, m.normal[i] = normal0;
      if (worst_of(m, around[i]) < kSearchBelow) search(i);
    }
  }
  // Then for the elements' shapes on the whole: the Laplacian target is the neighbours' mean, which
  // leaves a quad split from two near-equilateral triangles a 60-120 degree rhombus.
  for (int pass = 0; for_mean && passes > 0 && pass < kMeanPasses; ++pass)
    for (size_t i = first_free; i < n; ++i) {
      if (neighbours[i].empty()) continue;
      double reach = 0;
      for (Index j : neighbours[i]) reach += (m.uv[static_cast<size_t>(j)] - m.uv[i]).norm();
      raise_mean(m, map, i, around[i], kMeanStep * reach / static_cast<double>(neighbours[i].size()));
    }
  // What the passes left folded: rounds of search over the nodes of folded elements, then their
  // neighbours (a folded quad can need a neighbour moved first), while any is left.
  for (int round = 0; passes > 0 && round < kUnfoldRounds; ++round) {
    std::vector<size_t> folded;
    for (size_t i = first_free; i < n; ++i)
      if (!neighbours[i].empty() && !(worst_of(m, around[i]) > 0)) folded.push_back(i);
    if (folded.empty()) break;
    for (size_t i : folded) search(i);
    for (size_t i : folded)
      for (Index j : neighbours[i])
        if (static_cast<size_t>(j) >= first_free) search(static_cast<size_t>(j));
  }
}

void recombine(DomainMesh& m, double min_quality) {
  if (m.nodes_per_element != 3) return;
  const size_t nt = m.elements.size() / 3;
  std::vector<std::vector<size_t>> of_triangle;
  const std::vector<Candidate> cand = candidates(m, min_quality, of_triangle);
  // The best quads first, then one more quad per alternating path from each leftover triangle.
  std::vector<size_t> order(cand.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return cand[a].quality > cand[b].quality; });
  std::vector<std::int64_t> mate(nt, -1);
  for (size_t i : order) {
    const Candidate& c = cand[i];
    if (mate[static_cast<size_t>(c.t1)] < 0 && mate[static_cast<size_t>(c.t2)] < 0)
      mate[static_cast<size_t>(c.t1)] = mate[static_cast<size_t>(c.t2)] = static_cast<std::int64_t>(i);
  }
  std::vector<std::uint32_t> seen(nt, 0);
  std::uint32_t stamp = 0;
  for (size_t t = 0; t < nt; ++t)
    if (mate[t] < 0 && !of_triangle[t].empty()) augment(static_cast<Index>(t), cand, of_triangle, mate, seen, ++stamp);
  std::vector<Index> out;
  out.reserve(4 * nt);
  for (size_t t = 0; t < nt; ++t) {
    if (mate[t] < 0) {
      out.insert(out.end(), {m.elements[3 * t], m.elements[3 * t + 1], m.elements[3 * t + 2], -1});
      continue;
    }
    const Candidate& c = cand[static_cast<size_t>(mate[t])];
    if (static_cast<size_t>(c.t1) == t) out.insert(out.end(), c.quad.begin(), c.quad.end());  // once per pair
  }
  m.elements = std::move(out);
  m.nodes_per_element = 4;
}

void split_into_quads(DomainMesh& m, const SurfaceMap& map, SplitNodes place) {
  if (m.nodes_per_element != 4) return;
  const size_t ne = m.elements.size() / 4;
  const size_t n0 = m.uv.size();
  const Index nb = m.boundary_nodes;
  // Edges used once are on the boundary; hard edges are halved like them: a lift of the UV middle
  // would leave the hard edge's 3D curve wherever the UV chord skips a vertex of its chain.
  const HardEdges hard(m.hard_edges);
  std::unordered_map<std::uint64_t, int> uses;
  auto corners = [&](size_t e) { return static_cast<int>(wefm_common::element_corners(&m.elements[4 * e], 4)); };
  for (size_t e = 0; e < ne; ++e)
    for (int k = 0, n = corners(e); k < n; ++k) uses[edge_key(m.elements[4 * e + static_cast<size_t>(k)], m.elements[4 * e + static_cast<size_t>((k + 1) % n)])]++;
  // New nodes, numbered after the old ones for now; `boundary` marks those on the boundary.
  std::vector<P2> uv = m.uv;
  std::vector<Vec3> xyz = m.xyz, normal = m.normal;
  normal.resize(n0, Vec3::Zero());
  std::vector<char> boundary(n0, 0);
  for (Index k = 0; k < nb && static_cast<size_t>(k) < n0; ++k) boundary[static_cast<size_t>(k)] = 1;
  std::unordered_map<std::uint64_t, Index> mid;
  auto add = [&](const P2& p, bool on_boundary, const Vec3* chord) {
    Vec3 x, n = Vec3::Zero();
    map.lift(p, x, &n);
    uv.push_back(p), xyz.push_back(chord ? *chord : x), normal.push_back(n), boundary.push_back(on_boundary ? 1 : 0);
    return static_cast<Index>(uv.size() - 1);
  };
  auto midpoint = [&](Index a, Index b) {
    const auto [it, fresh] = mid.emplace(edge_key(a, b), 0);
    if (!fresh) return it->second;
    const bool fixed = uses[edge_key(a, b)] == 1 || hard.has(a, b);
    const P2 &ua = m.uv[static_cast<size_t>(a)], &ub = m.uv[static_cast<size_t>(b)];
    const Vec3 chord = 0.5 * (m.xyz[static_cast<size_t>(a)] + m.xyz[static_cast<size_t>(b)]);
    const P2 middle = 0.5 * (ua + ub);
    it->second = add(fixed || place == SplitNodes::uv_middles ? middle : nearest_on_segment(map, ua, ub, chord), fixed, fixed ? &chord : nullptr);
    return it->second;
  };
  std::vector<Index> out;
  out.reserve(4 * 4 * ne);
  for (size_t e = 0; e < ne; ++e) {
    const int n = corners(e);
    const Index* v = &m.elements[4 * e];
    P2 centroid = P2::Zero();
    Vec3 mean = Vec3::Zero();
    for (int k = 0; k < n; ++k) centroid += m.uv[static_cast<size_t>(v[k])], mean += m.xyz[static_cast<size_t>(v[k])];
    centroid /= n, mean /= n;
    Index ms[4];
    for (int k = 0; k < n; ++k) ms[k] = midpoint(v[k], v[(k + 1) % n]);
    // The centre nearest the corners' 3D mean, as long as the element's quads stay convex in UV; each
    // step short of the midpoints.
    P2 at = centroid;
    if (place == SplitNodes::nearest_3d) {
      double reach = HUGE_VAL;
      for (int k = 0; k < n; ++k) reach = std::min(reach, (uv[static_cast<size_t>(ms[k])] - centroid).norm());
      at = nearest_point(map, centroid, mean, 0.5 * reach);
    }
    const Index c = add(at, false, nullptr);
    auto quads_convex = [&] {
      for (int k = 0; k < n; ++k)
        if (!convex_in_uv(uv, {v[k], ms[k], c, ms[(k + n - 1) % n]})) return false;
      return true;
    };
    if (place == SplitNodes::nearest_3d && !quads_convex()) {
      uv[static_cast<size_t>(c)] = centroid;
      map.lift(centroid, xyz[static_cast<size_t>(c)], &normal[static_cast<size_t>(c)]);
    }
    for (int k = 0; k < n; ++k) out.insert(out.end(), {v[k], ms[k], c, ms[(k + n - 1) % n]});
  }
  // Boundary nodes first, as free meshes number them.
  std::vector<Index> renum(uv.size());
  Index next = 0;
  for (int pass = 1; pass >= 0; --pass)
    for (size_t k = 0; k < uv.size(); ++k)
      if (boundary[k] == pass) renum[k] = next++;
  m.uv.assign(uv.size(), P2::Zero());
  m.xyz.assign(uv.size(), Vec3::Zero());
  m.normal.assign(uv.size(), Vec3::Zero());
  Index boundary_count = 0;
  for (size_t k = 0; k < uv.size(); ++k) {
    const auto r = static_cast<size_t>(renum[k]);
    m.uv[r] = uv[k], m.xyz[r] = xyz[k], m.normal[r] = normal[k];
    boundary_count += boundary[k];
  }
  for (Index& i : out) i = renum[static_cast<size_t>(i)];
  m.elements = std::move(out);
  std::vector<std::array<Index, 2>> halves;
  for (const auto& e : m.hard_edges) {
    const auto it = mid.find(edge_key(e[0], e[1]));
    if (it == mid.end()) continue;  // not an edge of the mesh: nothing to keep
    const Index middle = renum[static_cast<size_t>(it->second)];
    for (const Index end : e) {
      const Index r = renum[static_cast<size_t>(end)];
      halves.push_back({std::min(r, middle), std::max(r, middle)});
    }
  }
  m.hard_edges = std::move(halves);
  m.boundary_nodes = boundary_count;
}

size_t split_count(const DomainMesh& m) {
  if (m.nodes_per_element != 4) return 0;
  size_t quads = 0;
  for (size_t e = 0; e < m.elements.size() / 4; ++e) quads += wefm_common::element_corners(&m.elements[4 * e], 4);
  return quads;
}

void split_and_smooth(DomainMesh& m, const SurfaceMap& map, int passes, double floor) {
  if (m.nodes_per_element != 4) return;
  DomainMesh other = m;
  split_into_quads(m, map, SplitNodes::nearest_3d);
  smooth_quads(m, map, passes, false);
  const double nearest = worst_of(m);
  if (!(nearest < floor)) return;
  split_into_quads(other, map, SplitNodes::uv_middles);
  smooth_quads(other, map, passes, false);
  if (worst_of(other) > nearest) m = std::move(other);
}

}  // namespace wefm::meshing
