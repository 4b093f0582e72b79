// Robust predicates and the triangulation on near-degenerate input: signs checked against exact
// integer arithmetic (coordinates are integers, so __int128 evaluates the determinants exactly).
#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <set>

#include "mesh_faces.hpp"
#include "wefm/core/meshing/predicates.hpp"
#include "wefm/core/meshing/triangulation.hpp"

using namespace wefm;
using meshing::P2;

namespace {

__extension__ typedef __int128 i128;  // GCC/Clang: exact products of 64-bit integers

int sign128(i128 v) { return v > 0 ? 1 : (v < 0 ? -1 : 0); }
int sign(double v) { return v > 0 ? 1 : (v < 0 ? -1 : 0); }

int exact_orient(std::int64_t ax, std::int64_t ay, std::int64_t bx, std::int64_t by, std::int64_t cx, std::int64_t cy) {
  return sign128(i128(ax - cx) * (by - cy) - i128(ay - cy) * (bx - cx));
}

int exact_incircle(const std::int64_t p[4][2]) {
  i128 m[3][3];
  for (int i = 0; i < 3; ++i) {
    const i128 dx = p[i][0] - p[3][0], dy = p[i][1] - p[3][1];
    m[i][0] = dx, m[i][1] = dy, m[i][2] = dx * dx + dy * dy;
  }
  return sign128(m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]) + m[1][2] * (m[2][0] * m[0][1] - m[2][1] * m[0][0]) +
                 m[2][2] * (m[0][0] * m[1][1] - m[0][1] * m[1][0]));
}

}  // namespace

TEST_CASE("orient2d has the exact sign on near-collinear points") {
  // Shewchuk's example: a point a few ulps off the line through (12, 12) and (24, 24). Scaled by
  // 2^53 every coordinate is an integer, so __int128 gives the exact sign.
  const double u = std::ldexp(1.0, -53);
  const std::int64_t S = std::int64_t(1) << 53;
  int wrong_naive = 0;
  for (int i = 0; i < 64; ++i)
    for (int j = 0; j < 64; ++j) {
      const P2 a(0.5 + i * u, 0.5 + j * u), b(12, 12), c(24, 24);
      const int e = exact_orient(S / 2 + i, S / 2 + j, 12 * S, 12 * S, 24 * S, 24 * S);
      CHECK(sign(meshing::orient2d(a, b, c)) == e);
      CHECK(sign(meshing::orient2d(b, c, a)) == e);
      CHECK(sign(meshing::orient2d(b, a, c)) == -e);
      const double naive = (a.x() - c.x()) * (b.y() - c.y()) - (a.y() - c.y()) * (b.x() - c.x());
      wrong_naive += sign(naive) != e;
    }
  MESSAGE("plain floating point got ", wrong_naive, " of 4096 signs wrong");
  CHECK(wrong_naive > 0);  // the input really is beyond plain floating point
}

TEST_CASE("incircle has the exact sign on near-cocircular points") {
  // Four exactly cocircular integer points (a 3-4-5 circle), translated, the fourth moved by at
  // most two units: determinants far below the rounding of the naive formula.
  std::mt19937_64 rng(11);
  const std::int64_t m = (std::int64_t(1) << 24) / 5;
  int wrong_naive = 0;
  for (int k = 0; k < 4000; ++k) {
    const std::int64_t tx = static_cast<std::int64_t>(rng() % (1u << 26)), ty = static_cast<std::int64_t>(rng() % (1u << 26));
    const std::int64_t dx = static_cast<std::int64_t>(rng() % 5) - 2, dy = static_cast<std::int64_t>(rng() % 5) - 2;
    const std::int64_t p[4][2] = {{3 * m + tx, 4 * m + ty}, {-5 * m + tx, ty}, {4 * m + tx, -3 * m + ty}, {tx + dx, 5 * m + ty + dy}};
    P2 q[4];
    for (int i = 0; i < 4; ++i) q[i] = P2(static_cast<double>(p[i][0]), static_cast<double>(p[i][1]));
    const int e = exact_incircle(p);  // (3,4), (-5,0), (4,-3) run counter-clockwise
    CHECK(sign(meshing::incircle(q[0], q[1], q[2], q[3])) == e);
    CHECK(sign(meshing::incircle(q[1], q[2], q[0], q[3])) == e);
    const double adx = q[0].x() - q[3].x(), ady = q[0].y() - q[3].y(), bdx = q[1].x() - q[3].x(), bdy = q[1].y() - q[3].y(),
                 cdx = q[2].x() - q[3].x(), cdy = q[2].y() - q[3].y();
    const double naive = (adx * adx + ady * ady) * (bdx * cdy - bdy * cdx) + (bdx * bdx + bdy * bdy) * (cdx * ady - cdy * adx) +
                         (cdx * cdx + cdy * cdy) * (adx * bdy - ady * bdx);
    wrong_naive += sign(naive) != e;
  }
  MESSAGE("plain floating point got ", wrong_naive, " of 4000 incircle signs wrong");
}

TEST_CASE("the triangulation stays valid on collinear and nearly collinear boundary nodes") {
  // A long thin rectangle whose long sides carry many exactly collinear nodes, plus a side whose
  // nodes deviate from the line by one unit in the last place.
  std::vector<P2> pts;
  const int n = 200;
  for (int k = 0; k < n; ++k) pts.emplace_back(0.1 + 0.7 * k / n, k % 2 ? std::nextafter(0.1, 1.0) : 0.1);
  pts.emplace_back(0.8, 0.1);
  pts.emplace_back(0.8, 0.1 + 1e-3);
  for (int k = n; k > 0; --k) pts.emplace_back(0.1 + 0.7 * k / n - 0.7 / n, 0.1 + 1e-3);
  std::vector<std::array<Index, 2>> segs;
  for (Index k = 0; k < static_cast<Index>(pts.size()); ++k) segs.push_back({k, (k + 1) % static_cast<Index>(pts.size())});
  meshing::Triangulation tr(pts, segs);
  CHECK(tr.valid());
  double area = 0;
  for (const auto& t : tr.triangles()) {
    const P2 a = tr.node(t[0]), b = tr.node(t[1]), c = tr.node(t[2]);
    CHECK(meshing::orient2d(a, b, c) > 0);
    area += 0.5 * ((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
  }
  CHECK(area == doctest::Approx(0.7 * 1e-3).epsilon(1e-6));
  CHECK(tr.triangles().size() == pts.size() - 2);
}

TEST_CASE("a long boundary loop triangulates constrained Delaunay, the same wherever the loop starts") {
  // 3000 nodes on a wavy ellipse, jittered so that no four are cocircular: the constrained Delaunay
  // triangulation is then unique, and the nodes' insertion order (randomised inside) cannot show.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-1e-4, 1e-4);
  const int n = 3000;
  std::vector<P2> pts;
  for (int k = 0; k < n; ++k) {
    const double a = 2 * kPi * k / n, r = 1 + 0.05 * std::sin(9 * a);
    pts.emplace_back(3 * r * std::cos(a) + jitter(rng), r * std::sin(a) + jitter(rng));
  }
  auto triangulate = [&](int start) {
    std::vector<P2> rotated;
    for (int k = 0; k < n; ++k) rotated.push_back(pts[static_cast<size_t>((k + start) % n)]);
    std::vector<std::array<Index, 2>> segs;
    for (Index k = 0; k < n; ++k) segs.push_back({k, (k + 1) % n});
    meshing::Triangulation tr(rotated, segs);
    CHECK(tr.valid());
    std::set<std::array<Index, 3>> out;
    for (auto t : tr.triangles()) {
      for (Index& v : t) v = (v + start) % n;  // back to the nodes' own numbers
      std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
      out.insert(t);
    }
    return out;
  };
  const auto tris = triangulate(0);
  CHECK(tris.size() == static_cast<size_t>(n - 2));
  CHECK(tris == triangulate(1234));
  // Constrained Delaunay: across every edge inside the loop, the opposite node is outside the circle.
  std::map<std::pair<Index, Index>, Index> apex;
  for (const auto& t : tris)
    for (int i = 0; i < 3; ++i) apex[{t[static_cast<size_t>(i)], t[static_cast<size_t>((i + 1) % 3)]}] = t[static_cast<size_t>((i + 2) % 3)];
  int violations = 0;
  for (const auto& [e, c] : apex) {
    const auto other = apex.find({e.second, e.first});
    if (other != apex.end() && meshing::incircle(pts[static_cast<size_t>(e.first)], pts[static_cast<size_t>(e.second)], pts[static_cast<size_t>(c)], pts[static_cast<size_t>(other->second)]) > 0) ++violations;
  }
  CHECK(violations == 0);
}

TEST_CASE("refinement keeps the triangulation constrained Delaunay and meets the angle bound") {
  std::vector<P2> pts;
  std::vector<std::array<Index, 2>> segs;
  for (int k = 0; k < 40; ++k) pts.emplace_back(std::cos(2 * kPi * k / 40), 0.5 * std::sin(2 * kPi * k / 40));
  for (Index k = 0; k < 40; ++k) segs.push_back({k, (k + 1) % 40});
  meshing::Triangulation tr(pts, segs);
  tr.refine([&](Index a, Index b, Index c) { return std::max({(tr.node(a) - tr.node(b)).norm(), (tr.node(b) - tr.node(c)).norm(), (tr.node(c) - tr.node(a)).norm()}) > 0.1 ? 1 : 0; },
            25 * kPi / 180, 0, [](Index) {});
  CHECK(tr.valid());
  CHECK(tr.node_count() > 100);
}

TEST_CASE("a boundary that touches itself is refused with invalid_state, not a crash") {
  // Two squares sharing a corner node (a figure eight): the node appears twice.
  const std::vector<P2> pts = {P2(0, 0), P2(1, 0), P2(1, 1), P2(0, 1), P2(1, 1), P2(2, 1), P2(2, 2), P2(1, 2)};
  const std::vector<std::array<Index, 2>> segs = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6}, {6, 7}, {7, 4}};
  try {
    meshing::Triangulation tr(pts, segs);
    FAIL("accepted a self-touching boundary");
  } catch (const Error& e) {
    CHECK(e.code() == Errc::invalid_state);
  }
  // A node lying inside another boundary segment.
  const std::vector<P2> pts2 = {P2(0, 0), P2(2, 0), P2(2, 2), P2(0, 2), P2(1, 0), P2(1, 1)};
  const std::vector<std::array<Index, 2>> segs2 = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 4}};
  CHECK_THROWS_AS(meshing::Triangulation(pts2, segs2), Error);
}

TEST_CASE("a segment given both ways is a scar: meshed as an edge with the domain on both sides") {
  // A square with a slit from the middle of its bottom side to its centre: the boundary runs up
  // one side of the slit and back down the other, through the same nodes.
  const std::vector<P2> pts = {P2(0, 0), P2(1, 0), P2(2, 0), P2(2, 2), P2(0, 2), P2(1, 1)};
  const std::vector<std::array<Index, 2>> segs = {{0, 1}, {1, 5}, {5, 1}, {1, 2}, {2, 3}, {3, 4}, {4, 0}};
  meshing::Triangulation tr(pts, segs);
  CHECK(tr.valid());
  double area = 0;
  int on_slit = 0;
  for (const auto& t : tr.triangles()) {
    area += 0.5 * meshing::orient2d(tr.node(t[0]), tr.node(t[1]), tr.node(t[2]));
    for (int k = 0; k < 3; ++k) on_slit += (t[k] == 1 && t[(k + 1) % 3] == 5) || (t[k] == 5 && t[(k + 1) % 3] == 1);
  }
  CHECK(area == doctest::Approx(4.0));  // the whole square: both sides of the slit are inside
  CHECK(on_slit == 2);                  // the slit is an edge of two triangles, one each side
  // Refinement never splits it and never puts a node on top of another.
  tr.refine([&](Index a, Index b, Index c) { return std::max({(tr.node(a) - tr.node(b)).norm(), (tr.node(b) - tr.node(c)).norm(), (tr.node(c) - tr.node(a)).norm()}) > 0.3 ? 1 : 0; },
            25 * kPi / 180, 0, [](Index) {});
  CHECK(tr.valid());
  for (const auto& t : tr.triangles()) CHECK(meshing::orient2d(tr.node(t[0]), tr.node(t[1]), tr.node(t[2])) > 1e-6);
}

TEST_CASE("boundary segments that cross are refused with invalid_state, not a leak of the outside") {
  // A bow tie: the loop's second and fourth segments cross.
  const std::vector<P2> pts = {P2(0, 0), P2(2, 0), P2(0, 2), P2(2, 2)};
  const std::vector<std::array<Index, 2>> segs = {{0, 1}, {1, 2}, {2, 3}, {3, 0}};
  try {
    meshing::Triangulation tr(pts, segs);
    FAIL("accepted crossing segments");
  } catch (const Error& e) {
    CHECK(e.code() == Errc::invalid_state);
  }
}

TEST_CASE("a refinement point within a rounding of a node is refused") {
  std::vector<P2> pts;
  std::vector<std::array<Index, 2>> segs;
  // The unit square, counter-clockwise, four segments a side (points at 1/8 from them encroach none).
  for (int k = 0; k < 4; ++k) pts.emplace_back(0.25 * k, 0.0);
  for (int k = 0; k < 4; ++k) pts.emplace_back(1.0, 0.25 * k);
  for (int k = 0; k < 4; ++k) pts.emplace_back(1.0 - 0.25 * k, 1.0);
  for (int k = 0; k < 4; ++k) pts.emplace_back(0.0, 1.0 - 0.25 * k);
  for (Index k = 0; k < 16; ++k) segs.push_back({k, (k + 1) % 16});
  meshing::Triangulation tr(pts, segs);
  // Refinement starts its search inside the domain (from outside, the walk stops at the boundary).
  auto inside = [&] {
    for (Index t = 0; t < tr.slot_count(); ++t)
      if (tr.live(t) && tr.inside(t)) return t;
    return Index(-1);
  };
  std::array<Index, 2> enc{{-1, -1}};
  const Index v = tr.insert(P2(0.55, 0.45), inside(), &enc);
  REQUIRE(v >= 0);
  CHECK(tr.insert(P2(std::nextafter(0.55, 1.0), 0.45), inside(), &enc) < 0);
  CHECK(tr.insert(P2(0.55, 0.45 + 1e-12), inside(), &enc) < 0);
  CHECK(tr.insert(P2(0.55, 0.6), inside(), &enc) >= 0);
  CHECK(tr.valid());
}
