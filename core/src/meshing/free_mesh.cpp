#include "wefm/core/meshing/free_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <set>
#include <unordered_set>

#include "wefm/core/sys/clock.hpp"
#include "wefm/core/sys/error.hpp"
#include "wefm/core/meshing/frontal.hpp"
#include "wefm/core/meshing/hard_edges.hpp"
#include "wefm/core/meshing/smoothing.hpp"
#include "wefm/core/meshing/triangulation.hpp"

namespace wefm::meshing {
namespace {

// Triangles the front left with sqrt(3) circumradius / size above this get their circumcentre.
constexpr double kRefineRatio = 1.6;

// A triangle whose longest 3D edge is more than this many times its longest UV edge stretched by the
// most the map stretches at its corners and centre straddles a jump of the lift: a domain that
// overlaps itself where the flattening folded (a random loft's face, bench/stress g5315 of seed 5001:
// 330 flipped facets) lifts points on either side of the fold far apart however close they are in
// UV. Splitting it only makes smaller triangles that straddle the same jump: there, refinement ran
// from 852 nodes to its budget of 7691, 20,000 triangles under a thousandth of the size in a spot
// 0.01 across, lambda_mesh 0.15. Within the map's facets a lifted chord is at most the largest
// stretch along it times its UV length; the margin covers stretches the four samples miss.
constexpr double kLiftJump = 10;

double largest_stretch(const SurfaceMap& map, const P2& p) {
  Eigen::Matrix<double, 3, 2> J;
  if (!map.jacobian(p, J)) return 0;
  const Eigen::Matrix2d M = J.transpose() * J;  // its larger eigenvalue is the stretch squared
  const double mid = 0.5 * (M(0, 0) + M(1, 1)), half = 0.5 * (M(0, 0) - M(1, 1));
  return std::sqrt(std::max(0.0, mid + std::sqrt(half * half + M(0, 1) * M(0, 1))));
}

// Asked for every triangle refinement would split for its size: the centre first, and the corners
// only while the stretch seen so far leaves the 3D edges unexplained (each sample locates a facet).
bool lift_jumps(const SurfaceMap& map, const P2& a, const P2& b, const P2& c, const Vec3& A, const Vec3& B, const Vec3& C) {
  const double uv = std::max({(a - b).norm(), (b - c).norm(), (c - a).norm()});
  const double xyz = std::max({(A - B).norm(), (B - C).norm(), (C - A).norm()});
  double stretch = 0;
  for (const P2& p : {P2((a + b + c) / 3), a, b, c}) {
    stretch = std::max(stretch, largest_stretch(map, p));
    if (stretch > 0 && !(xyz > kLiftJump * stretch * uv)) return false;
  }
  return stretch > 0;
}

// Boundary nodes closer than this fraction of the domain's extent are one node: the two sides of a
// scar (a repeated edge kept closed) lie on each other up to the solve's rounding.
constexpr double kSameNode = 1e-9;

// The loops' nodes as the triangulation's boundary: nodes at one point merged into one (their
// segments then come in both directions: a scar, meshed as an edge inside the domain), segments
// that merging shrank to a point dropped.
void boundary_nodes(const std::vector<LoopNodes>& loops, std::vector<P2>& pts, std::vector<Vec3>& xyz,
                    std::vector<std::array<Index, 2>>& segs) {
  std::vector<P2> all;
  for (const LoopNodes& l : loops) all.insert(all.end(), l.uv.begin(), l.uv.end());
  P2 lo(1e300, 1e300), hi(-1e300, -1e300);
  for (const P2& p : all) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const double tol = all.empty() ? 0 : kSameNode * (hi - lo).norm();
  std::vector<size_t> order(all.size());
  for (size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return all[a].x() < all[b].x(); });
  // Each loop node's representative: the first in loop order among those at its point, so the
  // boundary nodes keep the loops' order.
  std::vector<size_t> rep(all.size());
  for (size_t k = 0; k < rep.size(); ++k) rep[k] = k;
  auto root = [&](size_t k) {
    while (rep[k] != k) k = rep[k];
    return k;
  };
  for (size_t i = 0; i < order.size(); ++i)
    for (size_t j = i + 1; j < order.size() && all[order[j]].x() - all[order[i]].x() <= tol; ++j)
      if ((all[order[j]] - all[order[i]]).norm() <= tol) {
        const size_t a = root(order[i]), b = root(order[j]);
        rep[std::max(a, b)] = std::min(a, b);
      }
  std::vector<Index> node(all.size(), -1);
  std::vector<size_t> first_of;  // the representative loop node of each merged node
  for (size_t k = 0; k < all.size(); ++k) {
    const size_t r = root(k);
    if (node[r] < 0) {
      node[r] = static_cast<Index>(first_of.size());
      first_of.push_back(r);
    }
    node[k] = node[r];
  }
  std::vector<const Vec3*> at(all.size());
  size_t base = 0;
  for (const LoopNodes& l : loops) {
    const size_t n = l.uv.size();
    for (size_t k = 0; k < n; ++k) {
      at[base + k] = &l.xyz[k];
      const Index a = node[base + k], b = node[base + (k + 1) % n];
      if (a != b) segs.push_back({a, b});
    }
    base += n;
  }
  for (size_t r : first_of) {
    pts.push_back(all[r]);
    xyz.push_back(*at[r]);
  }
}

// The segments given both ways (a scar: the boundary runs along both its sides), once each.
std::vector<std::array<Index, 2>> scar_segments(const std::vector<std::array<Index, 2>>& segs) {
  auto directed_key = [](Index from, Index to) {
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(from)) << 32) | static_cast<std::uint32_t>(to);
  };
  std::unordered_set<std::uint64_t> directed;
  for (const auto& s : segs) directed.insert(directed_key(s[0], s[1]));
  std::vector<std::array<Index, 2>> out;
  for (const auto& s : segs)
    if (s[0] < s[1] && directed.count(directed_key(s[1], s[0]))) out.push_back(s);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

// Inserts the middles of edges between two boundary nodes that span the face (spans_face), until
// none is left or `rounds` passes: a face narrower than the size has no interior node of its own
// there. Before improvement, so that smoothing shapes the elements around the new nodes.
void split_spanning_edges(Triangulation& tr, const std::vector<Vec3>& xyz, Index boundary, const SurfaceMap& map, const SpanRule& span,
                          std::int64_t max_nodes, const std::function<void(Index)>& on_insert, int rounds) {
  for (int round = 0; round < rounds; ++round) {
    std::vector<std::pair<Index, P2>> middles;
    for (Index t = 0; t < tr.slot_count(); ++t) {
      if (!tr.live(t) || !tr.inside(t)) continue;
      for (int i = 0; i < 3; ++i) {
        const Index a = tr.corner(t, i), b = tr.corner(t, (i + 1) % 3);
        // Each edge once (from the side where a < b); segments are the caller's boundary.
        if (a >= boundary || b >= boundary || a > b || tr.constrained(t, i)) continue;
        if (spans_face(tr.node(a), tr.node(b), xyz[static_cast<size_t>(a)], xyz[static_cast<size_t>(b)], map, span))
          middles.emplace_back(t, 0.5 * (tr.node(a) + tr.node(b)));
      }
    }
    if (middles.empty()) return;
    for (const auto& [t, middle] : middles) {
      if (tr.node_count() >= max_nodes) return;
      const Index v = tr.insert(middle, t);
      if (v >= 0) on_insert(v);
    }
  }
}

// A cone's apex narrower than this in the domain (radians) gets nodes of its own across its wedge.
constexpr double kNarrowApex = kPi / 3;
// Up to where the wedge between the seam's two sides is this many seam segments wide.
constexpr double kWedgeSegments = 3;

// Nodes across the wedge at a narrow cone apex: the loop comes to a node A between two nodes at one
// 3D point (the seam's two sides, copies of one point, smoothing.hpp), and the seam's nodes pair up
// along both sides. A node joined to both copies of a seam node is one edge twice once the face's
// mesh is welded, and the mesher joins them wherever the wedge is narrower than its elements: each
// pair of copies whose chord is under kWedgeSegments seam segments gets two nodes at a third and two
// thirds of the chord, so that three edges go round the cone there. They are added to `pts` and
// `xyz` as nodes that never move; splitting edges later cannot make them (a node on a split edge is
// joined to both copies again), and refinement keeps away from segments that close.
void apex_wedge_nodes(const std::vector<LoopNodes>& loops, const SurfaceMap& map, std::vector<P2>& pts, std::vector<Vec3>& xyz) {
  auto copies = [](const LoopNodes& l, size_t a, size_t b) { return one_point(l.uv[a], l.uv[b], l.xyz[a], l.xyz[b]); };
  for (const LoopNodes& l : loops) {
    const size_t n = l.uv.size();
    if (n < 5) continue;
    std::set<std::pair<size_t, size_t>> done;  // pairs given nodes: a spindle's two apexes walk one seam
    for (size_t k = 0; k < n; ++k) {
      size_t prev = (k + n - 1) % n, next = (k + 1) % n;
      if (!copies(l, prev, next)) continue;
      const P2 apex = l.uv[k];
      const double reach = std::min((l.uv[prev] - apex).norm(), (l.uv[next] - apex).norm());
      if (!((l.uv[prev] - l.uv[next]).norm() < 2 * std::sin(kNarrowApex / 2) * reach)) continue;
      size_t before = k, after = k;  // the last pair's nodes on each side
      for (size_t ring = 0; ring < n / 2 && prev != next && copies(l, prev, next); ++ring) {
        const double segment = std::max((l.uv[prev] - l.uv[before]).norm(), (l.uv[next] - l.uv[after]).norm());
        const P2 chord = l.uv[prev] - l.uv[next];
        // A seam kept closed (a scar) has its copies at one UV point too: no wedge there.
        if (!(chord.norm() < kWedgeSegments * segment) || !(chord.norm() > kWedgeSegments * kSameNode * segment)) break;
        if (!done.insert(std::minmax(prev, next)).second) break;
        for (const double t : {1.0 / 3, 2.0 / 3}) {
          const P2 p = l.uv[next] + t * chord;
          Vec3 x;
          if (!map.lift(p, x)) continue;
          pts.push_back(p);
          xyz.push_back(x);
        }
        before = prev, after = next;
        prev = (prev + n - 1) % n, next = (next + 1) % n;
      }
    }
  }
}

}  // namespace

void free_mesh(const std::vector<LoopNodes>& loops, const SurfaceMap& map, const MeshOptions& o, double expected_elements,
               DomainMesh& out, const MeshControl& control) {
  double t0 = now();
  std::vector<P2> pts;
  std::vector<std::array<Index, 2>> segs;
  boundary_nodes(loops, pts, out.xyz, segs);
  apex_wedge_nodes(loops, map, pts, out.xyz);
  out.boundary_nodes = static_cast<Index>(pts.size());
  out.hard_edges = scar_segments(segs);
  Triangulation tr(pts, segs);
  const SizeField field(loops, o.size, kSizeGradation);
  std::vector<double> node_size(out.xyz.size());
  for (size_t k = 0; k < out.xyz.size(); ++k) node_size[k] = field.at(out.xyz[k]);
  std::int64_t inserted = 0;
  auto tick = [&] {
    // Throwing here leaves the triangulation consistent; it is discarded with the exception.
    // Insertions as the share of what the face's area asks for (refinement may run past it).
    if ((++inserted & 255) == 0) control.check(0.1 + 0.7 * std::min(1.0, static_cast<double>(inserted) / std::max(1.0, expected_elements / 2)));
  };
  // A triangulation has about twice as many triangles as nodes: stop refining near the cap. Without
  // one, refinement stops far past what the face's area and its boundary can need: a cascade of
  // insertions around a tiny angle must not run on until memory is gone.
  const std::int64_t budget = static_cast<std::int64_t>(std::min(4e9, 10 * expected_elements / 2 + 20.0 * static_cast<double>(pts.size()) + 1000));
  const std::int64_t max_nodes = o.max_elements > 0 ? std::min(o.max_elements / 2 + 1, budget) : budget;
  FrontalSettings fs;
  fs.max_nodes = max_nodes;
  frontal_refine(tr, out.xyz, node_size, map, field, fs, tick);
  // Circumcentre refinement for what the front left: triangles it could not place a node for.
  auto size_class = [&](Index a, Index b, Index c) {
    const Vec3 &A = out.xyz[static_cast<size_t>(a)], &B = out.xyz[static_cast<size_t>(b)], &C = out.xyz[static_cast<size_t>(c)];
    const double h = (node_size[static_cast<size_t>(a)] + node_size[static_cast<size_t>(b)] + node_size[static_cast<size_t>(c)]) / 3;
    if (size_ratio(A, B, C, h) > kRefineRatio) return lift_jumps(map, tr.node(a), tr.node(b), tr.node(c), A, B, C) ? -1 : 1;
    // Elements far below h are left to smoothing rather than split for their angles.
    return std::min({(A - B).norm(), (B - C).norm(), (C - A).norm()}) < 0.3 * h ? -1 : 0;
  };
  auto on_insert = [&](Index v) {
    tick();
    Vec3 x;
    map.lift(tr.node(v), x);
    if (out.xyz.size() <= static_cast<size_t>(v)) out.xyz.resize(static_cast<size_t>(v) + 1), node_size.resize(static_cast<size_t>(v) + 1);
    out.xyz[static_cast<size_t>(v)] = x;
    node_size[static_cast<size_t>(v)] = field.at(x);
  };
  tr.refine(size_class, o.min_angle_deg * kPi / 180.0, max_nodes, on_insert);
  // Spans shorter than half the size are a corner's or a cusp's, not a chord across the face, unless
  // the caller asks for every chord off the surface to be split (split_chords).
  const SpanRule span = o.split_chords ? SpanRule{0, kChordSag} : SpanRule{0.5 * o.size, kSpanSag};
  split_spanning_edges(tr, out.xyz, out.boundary_nodes, map, span, max_nodes, on_insert, 3);
  out.uv.resize(static_cast<size_t>(tr.node_count()));
  for (Index v = 0; v < tr.node_count(); ++v) out.uv[static_cast<size_t>(v)] = tr.node(v);
  auto tris = tr.triangles();
  out.report.time_mesh = now() - t0;

  control.check(0.8);
  t0 = now();
  improve_in_3d(out.uv, out.xyz, tris, out.boundary_nodes, HardEdges(out.hard_edges), o.smoothing_iterations, map, control, span);
  out.report.time_smooth = now() - t0;
  out.nodes_per_element = 3;
  for (const auto& t : tris) out.elements.insert(out.elements.end(), t.begin(), t.end());
}

}  // namespace wefm::meshing
