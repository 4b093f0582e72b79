// Automatic cuts (Options::auto_cut): annuli cut between their loops, closed genus-0 surfaces slit.
#include <cmath>
#include <functional>
#include <set>
#include <string>

#include "closed_meshes.hpp"
#include "solve_helpers.hpp"
#include "wefm/core/mesh/auto_cut.hpp"

using namespace wefm;

namespace {

Options auto_cut_on(double s = 1.0) {
  Options o = test::with_s(s);
  o.auto_cut = true;
  return o;
}

std::string error_of(const std::function<void()>& fn, Errc* code = nullptr) {
  try {
    fn();
  } catch (const Error& e) {
    if (code) *code = e.code();
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("the annulus cut is the shortest path between the loops, touching them only at its ends") {
  const TriMesh m = test::open_cylinder(32, 6);
  const AutoCut c = compute_auto_cut(m);
  CHECK(c.kind == AutoCutKind::Annulus);
  REQUIRE(c.seams.size() == 6);  // a generator: every other path zigzags and is longer
  CHECK(c.length == doctest::Approx(2.0).epsilon(1e-12));
  // Rows are 32 vertices each: the first row is one loop, the last the other.
  for (size_t j = 0; j < c.seams.size(); ++j) {
    const Index a = c.seams[j].first, b = c.seams[j].second;
    if (j > 0) CHECK((a >= 32 && a < 6 * 32));
    if (j + 1 < c.seams.size()) CHECK((b >= 32 && b < 6 * 32));
  }
  CHECK(compute_auto_cut(m).seams == c.seams);  // deterministic
}

TEST_CASE("an uncut open cylinder with auto_cut flattens to an exact rectangle with the cut periodic") {
  const TriMesh m = test::open_cylinder(32, 6);
  for (double s : {0.0, 1.0}) {
    CAPTURE(s);
    Face f;
    f.set_mesh(m);
    f.set_options(auto_cut_on(s));
    f.solve(nullptr, nullptr);
    const auto& r = f.result();
    const Topology& tp = f.topology();
    REQUIRE(tp.repeated.size() == 1);
    CHECK(tp.loops.size() == 1);
    CHECK(r.edge_modes[static_cast<size_t>(tp.repeated[0].edge)] == EdgeMode::Periodic);
    CHECK(r.report.auto_cut);
    CHECK(r.report.auto_cut_edges == 6);
    CHECK(r.report.auto_cut_length == doctest::Approx(2.0));
    CHECK_FALSE(r.report.auto_cut_uncut_kept);
    CHECK(r.report.auto_cut_other_score < r.report.quality.score);  // the uncut ring was tried and lost
    CHECK(r.report.quality.flips == 0);
    CHECK(r.report.quality.angle_max < 1 + 1e-7);
    const auto& e = tp.repeated[0];
    const Complex d0 = r.uv[e.side_a[0]] - r.uv[e.side_b[0]];
    for (size_t j = 1; j < e.side_a.size(); ++j) CHECK(std::abs(r.uv[e.side_a[j]] - r.uv[e.side_b[j]] - d0) < 1e-9 * std::abs(d0));
    CHECK(std::abs(d0) == doctest::Approx(2 * std::sin(kPi / 32) * 32).epsilon(1e-6));
  }
}

TEST_CASE("a flat ring with auto_cut is exact: the cut's two sides are glued back (scar)") {
  Face f;
  f.set_mesh(test::flat_ring(40, 6));
  f.set_options(auto_cut_on(1.0));
  f.solve(nullptr, nullptr);
  const auto& r = f.result();
  const Topology& tp = f.topology();
  REQUIRE(tp.repeated.size() == 1);
  CHECK(r.edge_modes[static_cast<size_t>(tp.repeated[0].edge)] == EdgeMode::Scar);
  CHECK(r.report.quality.flips == 0);
  CHECK(r.report.quality.angle_max < 1 + 1e-6);
  CHECK(r.report.quality.area_max < 1e-6);
  CHECK(r.report.auto_cut_other_score <= r.report.quality.score + 1e-9);  // uncut is exact too: a tie keeps the cut
}

TEST_CASE("a wavy ring keeps the uncut layout when it scores better, expressed on the cut's uses") {
  // z = 0.3 r sin(3 angle) over the ring 1 <= r <= 2: the uncut layout scores 0.9508, the cut one 0.9506.
  TriMesh m = test::flat_ring(48, 8);
  for (Vec3& p : m.vertices) p[2] = 0.3 * std::hypot(p[0], p[1]) * std::sin(3 * std::atan2(p[1], p[0]));
  Face f;
  f.set_mesh(m);
  f.set_options(auto_cut_on(1.0));
  f.solve(nullptr, nullptr);
  const auto& r = f.result();
  const Topology& tp = f.topology();
  REQUIRE(tp.repeated.size() == 1);
  MESSAGE("wavy ring: kept score " << r.report.quality.score << ", other (cut) " << r.report.auto_cut_other_score);
  CHECK(r.report.auto_cut_uncut_kept);
  CHECK(r.report.auto_cut_other_score < r.report.quality.score);
  CHECK(r.edge_modes[static_cast<size_t>(tp.repeated[0].edge)] == EdgeMode::Scar);
  CHECK(r.report.quality.flips == 0);
  CHECK(r.report.quality.boundary_intersections == 0);
  CHECK(r.uv.size() == tp.use_count);
  const auto& e = tp.repeated[0];
  for (size_t j = 0; j < e.side_a.size(); ++j) CHECK(r.uv[e.side_a[j]] == r.uv[e.side_b[j]]);
}

TEST_CASE("a closed sphere with auto_cut flattens with no flips and no boundary intersection") {
  Face f;
  f.set_mesh(test::icosphere(3));
  f.set_options(auto_cut_on(1.0));
  f.solve(nullptr, nullptr);
  const auto& q = f.result().report.quality;
  MESSAGE("icosphere (642 vertices): score " << q.score << ", angle mean " << q.angle_mean << " max " << q.angle_max << ", area mean "
                                             << q.area_mean << " max " << q.area_max << ", cut " << f.result().report.auto_cut_edges << " edges");
  CHECK(f.auto_cut().kind == AutoCutKind::Closed);
  CHECK(f.result().report.auto_cut);
  CHECK(q.flips == 0);
  CHECK(q.boundary_intersections == 0);
  CHECK(q.score > 0.3);
  CHECK(std::isnan(f.result().report.auto_cut_other_score));  // closed: nothing to compare with
}

TEST_CASE("a closed box is cut through its eight corners and unfolds to an exact net") {
  const TriMesh m = test::closed_box(Vec3(2, 1.4, 1), 12);
  const AutoCut c = compute_auto_cut(m);
  std::set<Index> corners;
  for (auto [a, b] : c.seams)
    for (Index v : {a, b}) {
      const Vec3& p = m.vertices[static_cast<size_t>(v)];
      if ((p[0] == 0 || p[0] == 2) && (p[1] == 0 || p[1] == 1.4) && (p[2] == 0 || p[2] == 1)) corners.insert(v);
    }
  CHECK(corners.size() == 8);
  Face f;
  f.set_mesh(m);
  f.set_options(auto_cut_on(1.0));
  f.solve(nullptr, nullptr);
  const auto& q = f.result().report.quality;
  CHECK(q.flips == 0);
  CHECK(q.boundary_intersections == 0);
  CHECK(q.angle_max < 1 + 1e-6);
  CHECK(q.area_max < 1e-6);
}

TEST_CASE("a smooth closed surface falls back to the farthest-pair slit") {
  const TriMesh m = test::icosphere(3, Vec3(1.6, 1, 0.7));
  const AutoCut c = compute_auto_cut(m);
  CHECK(c.seams == compute_auto_cut(m, SlitRule::FarthestPair).seams);
  // The double sweep is a heuristic: it ends near, not at, the ends of the long axis, on opposite
  // sides, about half an ellipse apart (3.66 between the axis ends).
  const Vec3 a = m.vertices[static_cast<size_t>(c.seams.front().first)], b = m.vertices[static_cast<size_t>(c.seams.back().second)];
  CHECK(a[0] * b[0] < 0);
  CHECK(std::abs(a[0]) > 1.0);
  CHECK(c.length > 3.3);
}

TEST_CASE("a closed torus with auto_cut fails with invalid_topology naming the genus") {
  Face f;
  f.set_mesh(test::torus(24, 12));
  f.set_options(auto_cut_on());
  Errc code{};
  const std::string msg = error_of([&] { f.solve(nullptr, nullptr); }, &code);
  CHECK(code == Errc::invalid_topology);
  CHECK(msg.find("genus 1") != std::string::npos);
  CHECK(msg.find("seams") != std::string::npos);
  CHECK_FALSE(f.has_result());
}

TEST_CASE("without auto_cut a closed surface is still refused, and the error offers seams or the automatic cut") {
  Face f;
  f.set_mesh(test::icosphere(1));
  Errc code{};
  const std::string msg = error_of([&] { f.solve(nullptr, nullptr); }, &code);
  CHECK(code == Errc::invalid_topology);
  CHECK(msg.find("automatic cut") != std::string::npos);
  CHECK(msg.find("not implemented") == std::string::npos);
  // The core names no C call; the C API adds wefm_face_add_seams and wefm_options.auto_cut (test_bad_input).
  try {
    f.solve(nullptr, nullptr);
  } catch (const Error& e) {
    CHECK(e.remedy() == Remedy::seams_or_cut);
  }
}

TEST_CASE("auto_cut leaves disks, faces with caller seams and faces with three loops alone") {
  CHECK(compute_auto_cut(test::flat_patch()).kind == AutoCutKind::None);
  CHECK(compute_auto_cut(test::disk_with_holes()).kind == AutoCutKind::None);
  std::vector<std::pair<Index, Index>> seam;
  const TriMesh m = test::open_cylinder(16, 4, &seam);
  Face f;
  f.set_mesh(m);
  f.set_options(auto_cut_on(0.0));
  f.add_seams(seam);
  f.solve(nullptr, nullptr);
  CHECK_FALSE(f.result().report.auto_cut);
  CHECK(f.auto_cut().kind == AutoCutKind::None);
}

TEST_CASE("switching auto_cut on an annulus changes its topology; on a disk it changes nothing") {
  Face f;
  f.set_mesh(test::open_cylinder(16, 4));
  const Index plain = f.topology().use_count;
  f.add_constraint({{{0, 1.0}}, 0.0});
  f.set_options(auto_cut_on());
  CHECK(f.constraints().empty());           // use ids changed: constraints go with them
  CHECK(f.topology().use_count == plain + 5);  // the cut's five vertices, doubled
  f.set_options(test::with_s(1.0));
  CHECK(f.topology().use_count == plain);

  Face d;
  d.set_mesh(test::flat_patch());
  d.topology();
  d.add_constraint({{{0, 1.0}}, 0.0});
  d.set_options(auto_cut_on());
  CHECK(d.constraints().size() == 1);
}
