#include "wefm/core/meshing/smoothing.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "wefm/core/mesh/union_find.hpp"
#include "wefm/core/meshing/mesh_quality.hpp"
#include "wefm/core/meshing/node_optimisation.hpp"
#include "wefm/core/meshing/node_triangles.hpp"

namespace wefm::meshing {

bool spans_face(const P2& ua, const P2& ub, const Vec3& a, const Vec3& b, const SurfaceMap& map, const SpanRule& rule, Vec3* middle) {
  const Vec3 e = b - a;
  // The two copies of a seam's end beside a cone's apex or a pole are one point in 3D: an edge
  // between them makes the triangle on it a fold (welded, it vanishes and the apex with it), however
  // short the edge. Only they are checked below the shortest span.
  const bool copies = one_point(ua, ub, a, b);
  if (!copies && !(e.squaredNorm() >= rule.shortest * rule.shortest)) return false;
  Vec3 x;
  if (!map.lift(0.5 * (ua + ub), x)) return false;
  if (middle) *middle = x;
  if (copies) return !one_point(ua, ub, a, x);
  // From the line, not from the chord's middle: where the flattening stretches, the UV middle lifts
  // to a point along the edge, not beside it.
  return (x - a).cross(e).norm() > rule.sag * e.squaredNorm();
}

namespace {

using Tri3 = std::array<Index, 3>;
// Passes of optimise_nodes after smoothing: on the CAD sample 3 gain 0.0008-0.007 in lambda_mesh
// over none, 6 no more than 0.0003 over 3. A move may lower a star's worst element down to the
// floor when the sum gains: with 0.8 the models' min lambda stays at or above 0.8 where it was
// higher (linkrods' 0.71 and Ball's 0.57 are boundary corners, untouched); 0.7 cost up to 0.1 in
// min lambda for 0.0005 more.
constexpr int kOptimisePasses = 3;
constexpr double kOptimiseFloor = 0.8;
// A node's compass search (48 lifts and star counts) runs when its star's worst element is below
// kCompassBelow; after a move to one of its two targets was kept, only below kCompassAfterMove:
// that move already shaped the star, and there the search mostly polished stars far above the
// quality floor, at the cost of most of smoothing's time (docs/PERFORMANCE.md, "Measurements
// behind design choices").
constexpr double kCompassBelow = 0.9;
constexpr double kCompassAfterMove = 0.6;
// Smoothing passes after the first kFullPasses move only nodes whose star's worst element is below
// kPolishBelow: by then the moves elsewhere polish stars far above the quality floor (over the 59
// cad-more models, passes 4 and 5 changed lambda_mesh by under 0.001) at the cost of a full pass
// each, while a graded square's worst element still needs them.
constexpr int kFullPasses = 3;
constexpr double kPolishBelow = 0.6;
// Issue 28's floor: triangles still below it after smoothing get a node of their own (split_pass).
constexpr double kSplitBelow = 0.3;
// Rounds of split_pass: a split's new triangles may need one more.
constexpr int kSplitRounds = 3;

double quality(const std::vector<P2>& uv, const std::vector<Vec3>& xyz, Index a, Index b, Index c) {
  if (!(orient2d(uv[static_cast<size_t>(a)], uv[static_cast<size_t>(b)], uv[static_cast<size_t>(c)]) > 0)) return -1;
  return lo_lambda(xyz[static_cast<size_t>(a)], xyz[static_cast<size_t>(b)], xyz[static_cast<size_t>(c)]);
}

// The triangle across the edge from -> to: the one holding to -> from, among the triangles listed
// around `at` (either end); -1 on the boundary. `apex` gets the position of its third node.
Index across(const NodeTriangles& around, const std::vector<Tri3>& tris, Index at, Index from, Index to, int* apex) {
  for (Index k = around.start[static_cast<size_t>(at)]; k < around.start[static_cast<size_t>(at) + 1]; ++k) {
    const Index u = around.items[static_cast<size_t>(k)];
    const Tri3& U = tris[static_cast<size_t>(u)];
    for (int m = 0; m < 3; ++m)
      if (U[static_cast<size_t>((m + 1) % 3)] == to && U[static_cast<size_t>((m + 2) % 3)] == from) return *apex = m, u;
  }
  return -1;
}

// Boundary nodes that are copies of one point: the two sides of a seam, the nodes of a degenerate
// edge at a pole. Welded into the model mesh they become one node, so a node joined to two copies
// of one point gets two edges on one 3D segment there, each with two triangles: beside a cone's
// apex, whose domain corner is narrower than about 150 degrees, a fan of two good triangles from the
// apex to one node across the cone is one triangle twice, once each way, and welding loses the apex.
class SeamCopies {
  // The unit, as a fraction of the boundary's 3D extent, in which copies are sorted together.
  static constexpr double kQuantum = 1e-7;

 public:
  // Boundary nodes (below `fixed`) closer in 3D than kSamePoint of their UV distance. Copies are one
  // point up to rounding, far below kQuantum of the boundary's extent: sorted by their points in those
  // units, they come together (each is also checked against the next two, for copies on either side
  // of a unit's edge in the last coordinate).
  SeamCopies(const std::vector<P2>& uv, const std::vector<Vec3>& xyz, Index fixed) : point_(static_cast<size_t>(fixed), -1) {
    if (fixed < 2) return;
    Vec3 lo = xyz[0], hi = xyz[0];
    for (Index v = 1; v < fixed; ++v) lo = lo.cwiseMin(xyz[static_cast<size_t>(v)]), hi = hi.cwiseMax(xyz[static_cast<size_t>(v)]);
    const double unit = kQuantum * (hi - lo).norm();
    if (!(unit > 0)) return;
    using Key = std::array<std::int64_t, 3>;
    std::vector<std::pair<Key, Index>> keys(static_cast<size_t>(fixed));
    for (Index v = 0; v < fixed; ++v) {
      Key k;
      for (int c = 0; c < 3; ++c) k[static_cast<size_t>(c)] = std::llround((xyz[static_cast<size_t>(v)][c] - lo[c]) / unit);
      keys[static_cast<size_t>(v)] = {k, v};
    }
    std::sort(keys.begin(), keys.end());
    UnionFind sets(fixed);
    for (size_t i = 0; i < keys.size(); ++i)
      for (size_t j = i + 1; j < keys.size() && (j <= i + 2 || keys[j].first == keys[i].first); ++j) {
        const Index p = keys[i].second, q = keys[j].second;
        if (one_point(uv[static_cast<size_t>(p)], uv[static_cast<size_t>(q)], xyz[static_cast<size_t>(p)], xyz[static_cast<size_t>(q)])) {
          sets.unite(p, q);
          point_[static_cast<size_t>(p)] = point_[static_cast<size_t>(q)] = 0;  // has a copy; labelled below
          any_ = true;
        }
      }
    for (Index v = 0; v < fixed; ++v)
      if (point_[static_cast<size_t>(v)] >= 0) point_[static_cast<size_t>(v)] = sets.find(v);
  }
  bool any() const { return any_; }
  // The point node v is a copy of (one of its copies' index), -1 for none.
  Index point(Index v) const { return static_cast<size_t>(v) < point_.size() ? point_[static_cast<size_t>(v)] : -1; }
  // Whether p and q are one point: the same node or copies.
  bool same(Index p, Index q) const { return p == q || (point(p) >= 0 && point(p) == point(q)); }

 private:
  std::vector<Index> point_;
  bool any_ = false;
};

// Whether node `from` (its triangles `around` it, current) has an edge to a copy of `to`'s point
// other than `to`.
bool joins_copy(const NodeTriangles& around, const std::vector<Tri3>& tris, const SeamCopies& copies, Index from, Index to) {
  if (copies.point(to) < 0) return false;
  for (Index k = around.start[static_cast<size_t>(from)]; k < around.start[static_cast<size_t>(from) + 1]; ++k) {
    const Tri3& U = tris[static_cast<size_t>(around.items[static_cast<size_t>(k)])];
    if (std::find(U.begin(), U.end(), from) == U.end()) continue;  // flipped away earlier in the pass
    for (Index q : U)
      if (q != to && q != from && copies.same(q, to)) return true;
  }
  return false;
}

// Whether flipping the edge b-c of (a, b, c) and (d, c, b) to (a, b, d) and (d, c, a) would make a
// fold: a new triangle on the same three points as the other or as a neighbour, once each way, or
// the new edge a-d beside an edge from one of its ends to a copy of the other's point (SeamCopies).
// `stale`: nodes that gained a triangle earlier in the pass, whose lists in `around` miss it; a flip
// that needs their edges waits for the next pass.
bool makes_fold(const NodeTriangles& around, const std::vector<Tri3>& tris, const SeamCopies& copies, const std::vector<char>& stale, Index a,
                Index b, Index c, Index d) {
  if (copies.same(b, c)) return true;
  // The neighbour across from -> to has its apex at `opposite`. Looked for around both ends: a
  // triangle flipped earlier in the pass is listed around the two corners it kept, not the new one.
  auto apex_is = [&](Index from, Index to, Index opposite) {
    int m = -1;
    Index u = across(around, tris, from, from, to, &m);
    if (u < 0) u = across(around, tris, to, from, to, &m);
    return u >= 0 && copies.same(tris[static_cast<size_t>(u)][static_cast<size_t>(m)], opposite);
  };
  if (apex_is(a, b, d) || apex_is(b, d, a) || apex_is(d, c, a) || apex_is(c, a, d)) return true;
  if (copies.point(a) < 0 && copies.point(d) < 0) return false;
  if (stale[static_cast<size_t>(a)] || stale[static_cast<size_t>(d)]) return true;
  return joins_copy(around, tris, copies, a, d) || joins_copy(around, tris, copies, d, a);
}

std::int64_t flip_pass(const std::vector<P2>& uv, const std::vector<Vec3>& xyz, std::vector<Tri3>& tris, Index fixed, const HardEdges& hard,
                       const SurfaceMap& map, const SpanRule& span, const SeamCopies& copies) {
  // The triangles around each node, as they were when the pass started (counting sort): the
  // neighbour across an edge is the other triangle around one of its ends that holds the edge
  // reversed. Flipped triangles are marked and left alone for the rest of the pass, so the stale
  // lists never mislead (makes_fold looks around both ends of an edge, and waits on nodes whose
  // lists miss a triangle). A hash of all edges cost 20 % of meshing time on a 145k-triangle square.
  const size_t nv = uv.size();
  const NodeTriangles around = node_triangles(nv, tris);
  std::vector<char> touched(tris.size(), 0), stale(nv, 0);
  // A triangle's quality is asked for once per edge; it cannot change before the triangle is
  // flipped (no node moves here), and a flipped triangle is not looked at again in this pass. Kept
  // per starting corner: lambda's rounding depends on the order of the corners.
  constexpr double kUnknown = -2;  // below any quality (-1 inverted, lambda >= 0)
  std::vector<double> known(3 * tris.size(), kUnknown);
  auto known_quality = [&](Index u, int first) {
    double& q = known[3 * static_cast<size_t>(u) + static_cast<size_t>(first)];
    if (q == kUnknown) {
      const Tri3& U = tris[static_cast<size_t>(u)];
      q = quality(uv, xyz, U[static_cast<size_t>(first)], U[static_cast<size_t>((first + 1) % 3)], U[static_cast<size_t>((first + 2) % 3)]);
    }
    return q;
  };
  std::int64_t flips = 0;
  for (Index t = 0; t < static_cast<Index>(tris.size()); ++t)
    for (int i = 0; i < 3 && !touched[static_cast<size_t>(t)]; ++i) {
      const Tri3 T = tris[static_cast<size_t>(t)];
      const Index a = T[static_cast<size_t>(i)], b = T[static_cast<size_t>((i + 1) % 3)], c = T[static_cast<size_t>((i + 2) % 3)];
      int j = -1;
      const Index s = across(around, tris, b, b, c, &j);
      // Each edge once, from its later triangle; an edge whose neighbour was flipped waits.
      if (s < 0 || s > t || touched[static_cast<size_t>(s)] || hard.has(b, c)) continue;
      const Tri3 S = tris[static_cast<size_t>(s)];
      const Index d = S[static_cast<size_t>(j)];
      const double old_q = std::min(known_quality(t, i), known_quality(s, 0));
      // min(q1, q2) > x needs q1 > x, so the second triangle is measured only when the first passes.
      const double q1 = quality(uv, xyz, a, b, d);
      if (!(q1 > old_q + 1e-9)) continue;
      const double new_q = std::min(q1, quality(uv, xyz, d, c, a));
      if (new_q > old_q + 1e-9 && !makes_fold(around, tris, copies, stale, a, b, c, d) && !(d < fixed && c < fixed && spans_face(uv[static_cast<size_t>(d)], uv[static_cast<size_t>(c)], xyz[static_cast<size_t>(d)], xyz[static_cast<size_t>(c)], map, span))) {
        tris[static_cast<size_t>(t)] = {a, b, d};
        tris[static_cast<size_t>(s)] = {d, c, a};
        touched[static_cast<size_t>(s)] = touched[static_cast<size_t>(t)] = 1;
        stale[static_cast<size_t>(a)] = stale[static_cast<size_t>(d)] = 1;
        ++flips;
      }
    }
  return flips;
}

// The triangles around one node and the qualities last measured on them, in the same order.
class NodeStar {
 public:
  NodeStar(const std::vector<P2>& uv, const std::vector<Vec3>& xyz, const std::vector<Tri3>& tris) : uv_(uv), xyz_(xyz), tris_(tris) {}
  void reset(const Index* first, const Index* last) { first_ = first, last_ = last, q_.resize(static_cast<size_t>(last - first)); }
  const Index* first() const { return first_; }
  const Index* last() const { return last_; }
  // Worst quality over the star, 1 for none. The count stops at a quality x for which `reject(x)`
  // holds (x rejects the position whatever the other triangles give); the value returned is then <= x.
  template <class Reject>
  double worst(Reject reject, bool uv_checked = false) {
    double w = 1;
    for (const Index* t = first_; t != last_; ++t) {
      const Tri3& T = tris_[static_cast<size_t>(*t)];
      const double x = uv_checked ? lo_lambda(xyz_[static_cast<size_t>(T[0])], xyz_[static_cast<size_t>(T[1])], xyz_[static_cast<size_t>(T[2])])
                                  : quality(uv_, xyz_, T[0], T[1], T[2]);
      q_[static_cast<size_t>(t - first_)] = x;
      w = std::min(w, x);
      if (reject(x)) return w;
    }
    return w;
  }
  double worst() {
    return worst([](double) { return false; });
  }
  // Sum of log quality from the last full count.
  double sum_log() const {
    double s = 0;
    for (double x : q_) s += std::log(std::max(x, 1e-300));
    return s;
  }
  // False when a UV triangle of the star is not positive: its quality would be -1, which rejects
  // any move, so the move need not be lifted to 3D.
  bool uv_positive() const {
    for (const Index* t = first_; t != last_; ++t) {
      const Tri3& T = tris_[static_cast<size_t>(*t)];
      if (!(orient2d(uv_[static_cast<size_t>(T[0])], uv_[static_cast<size_t>(T[1])], uv_[static_cast<size_t>(T[2])]) > 0)) return false;
    }
    return true;
  }

 private:
  const std::vector<P2>& uv_;
  const std::vector<Vec3>& xyz_;
  const std::vector<Tri3>& tris_;
  const Index *first_ = nullptr, *last_ = nullptr;
  std::vector<double> q_;
};

// Compass search on the worst element's quality around v, for nodes of poor elements.
bool compass_search(std::vector<P2>& uv, std::vector<Vec3>& xyz, const std::vector<Tri3>& tris, Index v, NodeStar& star, const P2& centroid,
                    const P2& ideal, const SurfaceMap& map, double below) {
  double now = star.worst();
  if (!(now < below)) return false;
  bool kept = false;
  const size_t vi = static_cast<size_t>(v);
  P2 best_p = uv[vi];
  Vec3 best_x = xyz[vi];
  double step = 0.25 * (centroid - ideal).norm() + 0.1 * (best_p - centroid).norm() + 1e-300;
  for (const Index* t = star.first(); t != star.last(); ++t)
    for (Index w : tris[static_cast<size_t>(*t)]) step = std::max(step, 0.15 * (uv[static_cast<size_t>(w)] - best_p).norm());
  P2 dirs[8];
  for (int dir = 0; dir < 8; ++dir) dirs[dir] = P2(std::cos(dir * kPi / 4), std::sin(dir * kPi / 4));
  for (int level = 0; level < 6; ++level, step *= 0.5)
    for (const P2& dir : dirs) {
      const P2 p = best_p + step * dir;
      uv[vi] = p;
      if (!star.uv_positive()) continue;
      Vec3 x;
      if (!map.lift(p, x)) continue;
      xyz[vi] = x;
      const double lim = now + 1e-12;
      const double q = star.worst([lim](double y) { return y <= lim; }, true);
      if (q > lim) now = q, best_p = p, best_x = x, kept = true;
    }
  uv[vi] = best_p, xyz[vi] = best_x;
  return kept;
}

// Moves node v (its triangles: `star`, reset to them) towards better shaped elements; true when it
// moved. A node whose star's worst element is not below `below` stays (2, above any quality: none).
bool move_node(std::vector<P2>& uv, std::vector<Vec3>& xyz, const std::vector<Tri3>& tris, Index v, NodeStar& star, const SurfaceMap& map,
               double below = 2) {
  const double before = star.worst();
  if (!(before < below)) return false;
  const size_t vi = static_cast<size_t>(v);
  // Two targets: the neighbours' centroid, and the mean of the apexes of the equilateral
  // triangles standing on the opposite edges (pulls a node towards well-shaped elements).
  P2 centroid = P2::Zero(), ideal = P2::Zero();
  int count = 0;
  for (const Index* t = star.first(); t != star.last(); ++t) {
    const Tri3& T = tris[static_cast<size_t>(*t)];
    int k = 0;
    while (T[static_cast<size_t>(k)] != v) ++k;
    const P2 a = uv[static_cast<size_t>(T[static_cast<size_t>((k + 1) % 3)])], b = uv[static_cast<size_t>(T[static_cast<size_t>((k + 2) % 3)])];
    const P2 e = b - a;
    ideal += 0.5 * (a + b) + (std::sqrt(3.0) / 2) * P2(-e.y(), e.x());
    centroid += a + b;
    count += 2;
  }
  centroid /= count;
  ideal /= static_cast<double>(star.last() - star.first());
  const double before_mean = star.sum_log();
  const P2 p0 = uv[vi];
  const Vec3 x0 = xyz[vi];
  bool kept = false;
  for (const P2& target : {ideal, centroid})
    for (double step : {1.0, 0.5}) {
      if (kept) break;
      const P2 p = p0 + step * (target - p0);
      uv[vi] = p;
      if (!star.uv_positive()) continue;
      Vec3 x;
      if (!map.lift(p, x)) continue;
      xyz[vi] = x;
      const double lim = before - 1e-12;
      const double after = star.worst([lim](double y) { return y < lim; }, true);
      // Better worst element, or as good a worst element and a better geometric mean.
      if (after > before + 1e-12 || (after >= lim && after > 0 && star.sum_log() > before_mean + 1e-12)) kept = true;
    }
  if (!kept) uv[vi] = p0, xyz[vi] = x0;
  if (compass_search(uv, xyz, tris, v, star, centroid, ideal, map, kept ? kCompassAfterMove : kCompassBelow)) kept = true;
  return kept;
}

// `below`: only nodes whose star's worst element is below it move.
std::int64_t smooth_pass(std::vector<P2>& uv, std::vector<Vec3>& xyz, const std::vector<Tri3>& tris, Index fixed, const SurfaceMap& map,
                         double below) {
  const NodeTriangles around = node_triangles(uv.size(), tris);
  NodeStar star(uv, xyz, tris);
  std::int64_t moves = 0;
  for (Index v = fixed; v < static_cast<Index>(uv.size()); ++v) {
    const size_t vi = static_cast<size_t>(v);
    const Index* first = around.items.data() + around.start[vi];
    const Index* last = around.items.data() + around.start[vi + 1];
    if (first == last) continue;
    star.reset(first, last);
    if (move_node(uv, xyz, tris, v, star, map, below)) ++moves;
  }
  return moves;
}

// Splits, for each triangle below kSplitBelow, its longest edge inside the domain at the UV midpoint
// and moves the new node, then the corners of the two split triangles that are inside the domain,
// then the new node again; kept only when the worst of the triangles this changed beats the worst
// before.
// A needle between a fine boundary chain and a coarse one across a strip narrower than h has no
// interior node at all, and a sliver whose apex sits on a boundary edge cannot leave it while its
// other triangles hold it there: no move of the existing nodes mends either.
// One function of about 100 lines: the split, its moves and its undo share the pass's bookkeeping
// (the triangles added per node, those touched, the stars), which steps of their own would pass round.
std::int64_t split_pass(std::vector<P2>& uv, std::vector<Vec3>& xyz, std::vector<Tri3>& tris, Index fixed, const HardEdges& hard, const SurfaceMap& map) {
  std::vector<Index> bad;
  for (Index t = 0; t < static_cast<Index>(tris.size()); ++t) {
    const Tri3& T = tris[static_cast<size_t>(t)];
    const double q = quality(uv, xyz, T[0], T[1], T[2]);
    if (q >= 0 && q < kSplitBelow) bad.push_back(t);
  }
  if (bad.empty()) return 0;
  // As at the pass's start; changed triangles are marked and their neighbours found by content.
  const NodeTriangles around = node_triangles(uv.size(), tris);
  const Index old_nodes = static_cast<Index>(uv.size());
  std::vector<char> touched(tris.size(), 0);
  // Per node (the pass's new nodes included), the triangles the pass added on it, in the order
  // added: added triangles never change, and a rejected split takes its two back.
  std::vector<std::vector<Index>> added(uv.size());
  std::int64_t splits = 0;
  for (const Index t : bad) {
    if (touched[static_cast<size_t>(t)]) continue;
    const Tri3 T = tris[static_cast<size_t>(t)];
    Index s = -1, a = -1, b = -1, c = -1, d = -1;
    double longest = -1;
    for (int i = 0; i < 3; ++i) {
      const Index ai = T[static_cast<size_t>(i)], bi = T[static_cast<size_t>((i + 1) % 3)], ci = T[static_cast<size_t>((i + 2) % 3)];
      const double len = (xyz[static_cast<size_t>(bi)] - xyz[static_cast<size_t>(ci)]).norm();
      if (len <= longest || hard.has(bi, ci)) continue;
      int m = -1;
      const Index u = across(around, tris, bi, bi, ci, &m);
      if (u < 0 || touched[static_cast<size_t>(u)]) continue;
      s = u, a = ai, b = bi, c = ci, d = tris[static_cast<size_t>(u)][static_cast<size_t>(m)], longest = len;
    }
    if (s < 0) continue;
    const Tri3 S = tris[static_cast<size_t>(s)];
    // The split also lets the corners inside the domain move (a sliver's apex a rounding off a
    // boundary edge), which changes their other triangles.
    const std::array<Index, 4> corners{a, b, c, d};
    // A node's triangles: those around it at the pass's start that still hold it, and the new ones.
    auto star_of = [&](Index w) {
      std::vector<Index> st;
      auto holds = [&](Index u) {
        const Tri3& U = tris[static_cast<size_t>(u)];
        return U[0] == w || U[1] == w || U[2] == w;
      };
      if (w < old_nodes)
        for (Index k = around.start[static_cast<size_t>(w)]; k < around.start[static_cast<size_t>(w) + 1]; ++k)
          if (holds(around.items[static_cast<size_t>(k)])) st.push_back(around.items[static_cast<size_t>(k)]);
      const auto& mine = added[static_cast<size_t>(w)];
      st.insert(st.end(), mine.begin(), mine.end());
      return st;
    };
    // The worst of the given triangles and of the triangles at the corners inside the domain: the
    // triangles a split and its moves change (a fan of needles at a boundary corner keeps the
    // corner's worst until its last needle is split, so the corners' other triangles are not judged).
    auto worst_of = [&](const std::vector<Index>& ts) {
      double q = 1;
      std::vector<Index> all = ts;
      for (Index w : corners)
        if (w >= fixed)
          for (Index u : star_of(w)) all.push_back(u);
      for (Index u : all) q = std::min(q, quality(uv, xyz, tris[static_cast<size_t>(u)][0], tris[static_cast<size_t>(u)][1], tris[static_cast<size_t>(u)][2]));
      return q;
    };
    const double before = worst_of({t, s});
    const P2 p = 0.5 * (uv[static_cast<size_t>(b)] + uv[static_cast<size_t>(c)]);
    Vec3 x;
    if (!map.lift(p, x)) continue;
    std::array<P2, 4> uv0;
    std::array<Vec3, 4> xyz0;
    for (size_t k = 0; k < 4; ++k) uv0[k] = uv[static_cast<size_t>(corners[k])], xyz0[k] = xyz[static_cast<size_t>(corners[k])];
    const Index v = static_cast<Index>(uv.size());
    uv.push_back(p), xyz.push_back(x);
    const Index t2 = static_cast<Index>(tris.size()), s2 = t2 + 1;
    tris[static_cast<size_t>(t)] = {a, b, v}, tris[static_cast<size_t>(s)] = {d, c, v};
    tris.push_back({a, v, c}), tris.push_back({d, v, b});
    added.emplace_back();
    for (Index w : {a, v, c}) added[static_cast<size_t>(w)].push_back(t2);
    for (Index w : {d, v, b}) added[static_cast<size_t>(w)].push_back(s2);
    const std::vector<Index> star{t, s, t2, s2};
    NodeStar moving(uv, xyz, tris);
    auto move = [&](Index w, const std::vector<Index>& ts) {
      moving.reset(ts.data(), ts.data() + ts.size());
      move_node(uv, xyz, tris, w, moving, map);
    };
    move(v, star);
    bool inner = false;
    for (Index w : corners)
      if (w >= fixed) move(w, star_of(w)), inner = true;
    if (inner) move(v, star);
    if (worst_of(star) > before + 1e-9) {
      touched[static_cast<size_t>(t)] = touched[static_cast<size_t>(s)] = 1;
      ++splits;
    } else {
      tris[static_cast<size_t>(t)] = T, tris[static_cast<size_t>(s)] = S;
      tris.resize(static_cast<size_t>(t2));
      for (Index w : {b, v, d}) added[static_cast<size_t>(w)].pop_back();
      for (Index w : {c, v, a}) added[static_cast<size_t>(w)].pop_back();
      added.pop_back();
      uv.pop_back(), xyz.pop_back();
      for (size_t k = 0; k < 4; ++k) uv[static_cast<size_t>(corners[k])] = uv0[k], xyz[static_cast<size_t>(corners[k])] = xyz0[k];
    }
  }
  return splits;
}

// Splits the edge a -> b of triangle t = (a, b, c), with s = (b, a, d) across it, at its UV middle
// lifted to `x`: four triangles around the new node, which then moves for their worst quality.
void split_edge(std::vector<P2>& uv, std::vector<Vec3>& xyz, std::vector<Tri3>& tris, Index t, Index s, Index d, const Vec3& x, NodeStar& star,
                const SurfaceMap& map) {
  const Tri3 T = tris[static_cast<size_t>(t)];
  const Index a = T[0], b = T[1], c = T[2];
  const Index v = static_cast<Index>(uv.size());
  uv.push_back(0.5 * (uv[static_cast<size_t>(a)] + uv[static_cast<size_t>(b)])), xyz.push_back(x);
  const Index t2 = static_cast<Index>(tris.size());
  tris[static_cast<size_t>(t)] = {a, v, c}, tris[static_cast<size_t>(s)] = {b, v, d};
  tris.push_back({v, b, c}), tris.push_back({v, a, d});
  const std::array<Index, 4> four{t, s, t2, t2 + 1};
  star.reset(four.data(), four.data() + 4);
  move_node(uv, xyz, tris, v, star, map);
}

// Splits edges between two boundary nodes that span the face (spans_face) at their UV middle,
// lifted, the new node then moved for the worst quality of its four triangles. The mesher splits
// them before improvement and flips never make one; this mends what the moves left. Returns the
// number of edges split; an edge whose triangle another split changed waits for the next call.
std::int64_t split_spanning(std::vector<P2>& uv, std::vector<Vec3>& xyz, std::vector<Tri3>& tris, Index fixed, const HardEdges& hard,
                            const SurfaceMap& map, const SpanRule& span) {
  const NodeTriangles around = node_triangles(uv.size(), tris);
  std::vector<char> touched(tris.size(), 0);
  NodeStar star(uv, xyz, tris);
  std::int64_t splits = 0;
  const Index count = static_cast<Index>(tris.size());
  for (Index t = 0; t < count; ++t)
    for (int i = 0; i < 3 && !touched[static_cast<size_t>(t)]; ++i) {
      const Tri3 T = tris[static_cast<size_t>(t)];
      const Index a = T[static_cast<size_t>(i)], b = T[static_cast<size_t>((i + 1) % 3)];
      if (a >= fixed || b >= fixed || hard.has(a, b)) continue;
      int m = -1;
      const Index s = across(around, tris, a, a, b, &m);
      if (s < 0 || touched[static_cast<size_t>(s)]) continue;  // a boundary segment, or changed already
      Vec3 x;
      if (!spans_face(uv[static_cast<size_t>(a)], uv[static_cast<size_t>(b)], xyz[static_cast<size_t>(a)], xyz[static_cast<size_t>(b)], map, span, &x)) continue;
      tris[static_cast<size_t>(t)] = {a, b, T[static_cast<size_t>((i + 2) % 3)]};
      split_edge(uv, xyz, tris, t, s, tris[static_cast<size_t>(s)][static_cast<size_t>(m)], x, star, map);
      touched[static_cast<size_t>(t)] = touched[static_cast<size_t>(s)] = 1;
      ++splits;
    }
  return splits;
}

// Splits the edges that join a node to two copies of one point (SeamCopies), each at its UV middle:
// welded, each pair would be one edge of four triangles, or, beside a cone's apex, a fold that takes
// the apex with it. The fan there then gets four triangles. Edges on the boundary stay (the apex
// itself joins both copies along the seam), and so does an edge whose triangles another split
// changed in this call. Returns the edges split.
std::int64_t split_folds(std::vector<P2>& uv, std::vector<Vec3>& xyz, std::vector<Tri3>& tris, const HardEdges& hard, const SurfaceMap& map,
                         const SeamCopies& copies) {
  if (!copies.any()) return 0;
  // (node, point, copy) for every edge from a node to a copy of a point other than its own; and
  // (node, point) for every triangle from a node to two copies of one point (along a degenerate edge
  // at a pole), which welding drops, leaving one edge where there were two.
  std::vector<std::array<Index, 3>> joins;
  std::vector<std::array<Index, 2>> collapsing;
  for (const Tri3& T : tris)
    for (size_t i = 0; i < 3; ++i) {
      const Index p = T[i], q = T[(i + 1) % 3], r = T[(i + 2) % 3];
      if (copies.point(q) >= 0 && !copies.same(p, q)) joins.push_back({p, copies.point(q), q});
      if (copies.point(p) >= 0 && !copies.same(p, q)) joins.push_back({q, copies.point(p), p});
      if (q != r && copies.same(q, r) && !copies.same(p, q)) collapsing.push_back({p, copies.point(q)});
    }
  std::sort(joins.begin(), joins.end());
  joins.erase(std::unique(joins.begin(), joins.end()), joins.end());
  std::sort(collapsing.begin(), collapsing.end());
  const NodeTriangles around = node_triangles(uv.size(), tris);
  std::vector<char> touched(tris.size(), 0);
  NodeStar star(uv, xyz, tris);
  std::int64_t splits = 0;
  // Splits the inner edge x-q from a triangle around x that holds it, unless changed already.
  auto split = [&](Index x, Index q) {
    for (Index k = around.start[static_cast<size_t>(x)]; k < around.start[static_cast<size_t>(x) + 1]; ++k) {
      const Index u = around.items[static_cast<size_t>(k)];
      const Tri3 U = tris[static_cast<size_t>(u)];
      for (size_t i = 0; i < 3; ++i) {
        const Index p = U[i], r = U[(i + 1) % 3];
        if (!((p == x && r == q) || (p == q && r == x))) continue;
        int m = -1;
        const Index w = across(around, tris, p, p, r, &m);
        if (w < 0 || touched[static_cast<size_t>(u)] || touched[static_cast<size_t>(w)] || hard.has(p, r)) return;
        Vec3 mid;
        if (!map.lift(0.5 * (uv[static_cast<size_t>(p)] + uv[static_cast<size_t>(r)]), mid)) return;
        tris[static_cast<size_t>(u)] = {p, r, U[(i + 2) % 3]};
        split_edge(uv, xyz, tris, u, w, tris[static_cast<size_t>(w)][static_cast<size_t>(m)], mid, star, map);
        touched[static_cast<size_t>(u)] = touched[static_cast<size_t>(w)] = 1;
        ++splits;
        return;
      }
    }
  };
  for (size_t g = 0; g < joins.size();) {
    size_t e = g + 1;
    while (e < joins.size() && joins[e][0] == joins[g][0] && joins[e][1] == joins[g][1]) ++e;
    // k copies joined by k - 1 collapsing triangles weld into one edge.
    const std::array<Index, 2> key{joins[g][0], joins[g][1]};
    const auto chain = std::equal_range(collapsing.begin(), collapsing.end(), key);
    if (e - g >= 2 && static_cast<size_t>(chain.second - chain.first) + 1 < e - g)
      for (size_t k = g; k < e; ++k) split(joins[k][0], joins[k][2]);
    g = e;
  }
  return splits;
}

}  // namespace

std::int64_t improve_in_3d(std::vector<P2>& uv, std::vector<Vec3>& xyz, std::vector<Tri3>& tris, Index fixed, const HardEdges& hard, int iterations,
                           const SurfaceMap& map,
                           const MeshControl& control, const SpanRule& span) {
  // Each pass over a face of millions of triangles takes a while: the caller's stop is heard
  // between passes, and the fraction reported climbs from 0.8 towards 0.95 pass by pass.
  int passes = 0;
  auto check = [&] {
    ++passes;
    control.check(0.8 + 0.15 * passes / (passes + 8.0));
  };
  // Flip passes until few flips remain; stop smoothing once a pass moves almost nothing: the last
  // sweeps of a converged mesh cost a full pass each and change no figure.
  const std::int64_t few_flips = std::max<std::int64_t>(1, static_cast<std::int64_t>(tris.size()) / 1000);
  const std::int64_t few_moves = std::max<std::int64_t>(1, (static_cast<std::int64_t>(uv.size()) - fixed) / 200);
  const SeamCopies copies(uv, xyz, fixed);
  auto flips = [&] {
    for (int k = 0; k < 8; ++k) {
      check();
      if (flip_pass(uv, xyz, tris, fixed, hard, map, span, copies) < few_flips) break;
    }
  };
  // Before the flips: they never make such an edge (makes_fold), and the moves shape the new nodes' stars.
  for (int it = 0; it < kSplitRounds; ++it)
    if (split_folds(uv, xyz, tris, hard, map, copies) == 0) break;
  std::int64_t total = 0;
  for (int it = 0; it < iterations; ++it) {
    flips();
    check();
    const bool full = it < kFullPasses;
    const std::int64_t m = smooth_pass(uv, xyz, tris, fixed, map, full ? 2.0 : kPolishBelow);
    total += m;
    if (full ? m < few_moves : m == 0) break;
  }
  flips();
  // Then the nodes move for lambda_mesh itself (sum of log lambda), flips after each pass.
  for (int it = 0; it < std::min(iterations, kOptimisePasses); ++it) {
    check();
    if (optimise_nodes(uv, xyz, tris, fixed, map, kOptimiseFloor) == 0) break;
    flips();
  }
  for (int it = 0; it < kSplitRounds; ++it) {
    check();
    if (split_pass(uv, xyz, tris, fixed, hard, map) == 0) break;
    flips();
  }
  for (int it = 0; it < kSplitRounds; ++it) {
    check();
    if (split_spanning(uv, xyz, tris, fixed, hard, map, span) == 0) break;
  }
  return total;
}

}  // namespace wefm::meshing
