// METHOD §10: developable faces flatten with zero distortion; the paper's pyramid example.
#include <cmath>
#include <map>

#include "solve_helpers.hpp"

using namespace wefm;

TEST_CASE("a flat patch flattens with zero distortion for every s, with and without the boundary term") {
  for (double s : {0.0, 0.3, 1.0})
    for (double mu : {0.0, 1.0}) {
      CAPTURE(s);
      CAPTURE(mu);
      const auto r = test::solve(test::flat_patch(), test::with_s(s, mu));
      CHECK(r.report.quality.flips == 0);
      CHECK(r.report.quality.angle_max < 1 + 1e-8);
      CHECK(r.report.quality.area_max < 1e-8);
    }
}

TEST_CASE("a cylinder cut open flattens with zero distortion") {
  for (double s : {0.0, 0.3, 1.0}) {
    CAPTURE(s);
    const auto r = test::solve(test::cut_open_cylinder(24, 6), test::with_s(s));
    CHECK(r.report.quality.flips == 0);
    CHECK(r.report.quality.angle_max < 1 + 1e-7);
    CHECK(r.report.quality.area_max < 1e-7);
  }
}

TEST_CASE("the paper's five-triangle pyramid, cut from apex to a base corner, flattens to equilateral triangles") {
  const ReadResult rr = read_mesh(std::string(WEFM_TEST_DATA) + "/pyramid5.obj", 0);
  Face f;
  f.set_mesh(rr.mesh);
  Options o;
  o.s = 0;
  f.set_options(o);
  f.add_seams({{0, 1}});
  f.solve(nullptr, nullptr);
  const auto& r = f.result();
  const Topology& tp = f.topology();
  CHECK(tp.use_count == 7);  // apex opened once, corner 1 split in two
  for (size_t t = 0; t < rr.mesh.triangles.size(); ++t)
    for (int j = 0; j < 3; ++j) {
      const double l = std::abs(r.uv[tp.corner_use[3 * t + j]] - r.uv[tp.corner_use[3 * t + (j + 1) % 3]]);
      CHECK(l == doctest::Approx(1.0).epsilon(1e-8));
    }
  CHECK(r.report.quality.angle_max < 1 + 1e-8);
}

TEST_CASE("an open cylinder with its seam periodic flattens to an exact rectangle whose seam sides are translates") {
  std::vector<std::pair<Index, Index>> seam;
  const TriMesh m = test::open_cylinder(32, 6, &seam);
  for (double s : {0.0, 1.0}) {
    CAPTURE(s);
    Face f;
    f.set_mesh(m);
    Options o = test::with_s(s);
    o.default_edge_mode = EdgeMode::Periodic;
    f.set_options(o);
    f.add_seams(seam);
    f.solve(nullptr, nullptr);
    const auto& r = f.result();
    const Topology& tp = f.topology();
    REQUIRE(tp.repeated.size() == 1);
    CHECK(r.edge_modes[static_cast<size_t>(tp.repeated[0].edge)] == EdgeMode::Periodic);
    CHECK(r.report.quality.angle_max < 1 + 1e-7);
    CHECK(r.report.quality.flips == 0);
    const auto& e = tp.repeated[0];
    const Complex d0 = r.uv[e.side_a[0]] - r.uv[e.side_b[0]];
    for (size_t j = 1; j < e.side_a.size(); ++j) CHECK(std::abs(r.uv[e.side_a[j]] - r.uv[e.side_b[j]] - d0) < 1e-9 * std::abs(d0));
    CHECK(std::abs(d0) == doctest::Approx(2 * std::sin(kPi / 32) * 32).epsilon(1e-6));  // the circumference as a polygon
  }
}

TEST_CASE("automatic mode picks periodic for the open cylinder's seam") {
  std::vector<std::pair<Index, Index>> seam;
  const TriMesh m = test::open_cylinder(32, 6, &seam);
  const auto r = test::solve(m, test::with_s(0), seam, EdgeMode::Auto);
  const auto& sc = r.edge_scores[0];
  MESSAGE("scores free " << sc[1] << " periodic " << sc[2] << " scar " << sc[3] << " rotational " << sc[4]);
  CHECK(r.edge_modes[0] == EdgeMode::Periodic);
  CHECK(sc[2] >= sc[1] - 1e-12);
  CHECK(sc[2] > sc[3]);
}

TEST_CASE("a helical strip of 2.5 turns on a cylinder, seamed along its length, flattens exactly; automatic picks periodic") {
  // The strip t in [0, 2.5 turns], height one pitch: its upper edge over turn k is its lower edge
  // over turn k + 1, so those vertices are shared and the shared helix is a seam along its length.
  const int per = 48, n = 120, m = 4;
  const double pitch = 0.6;
  TriMesh mesh;
  std::map<std::pair<int, int>, Index> id;
  auto vid = [&](int i, int j) {
    if (j == m && i + per <= n) i += per, j = 0;
    auto it = id.find({i, j});
    if (it != id.end()) return it->second;
    const double t = 2 * kPi * i / per;
    mesh.vertices.emplace_back(std::cos(t), std::sin(t), pitch * i / per + pitch * j / m);
    return id[{i, j}] = static_cast<Index>(mesh.vertices.size() - 1);
  };
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) {
      const Index a = vid(i, j), b = vid(i + 1, j), c = vid(i, j + 1), d = vid(i + 1, j + 1);
      mesh.triangles.push_back({a, b, d});
      mesh.triangles.push_back({a, d, c});
    }
  std::vector<std::pair<Index, Index>> seam;
  for (int i = per; i < n; ++i) seam.emplace_back(vid(i, 0), vid(i + 1, 0));
  const auto r = test::solve(mesh, test::with_s(1.0), seam, EdgeMode::Auto);
  // The repeated edge is the one the automatic decision scored.
  size_t e = r.edge_scores.size();
  for (size_t k = 0; k < r.edge_scores.size(); ++k)
    if (std::isfinite(r.edge_scores[k][static_cast<size_t>(EdgeMode::Periodic)])) e = k;
  REQUIRE(e < r.edge_scores.size());
  const auto& sc = r.edge_scores[e];
  MESSAGE("helical strip: free " << sc[static_cast<size_t>(EdgeMode::Free)] << ", periodic " << sc[static_cast<size_t>(EdgeMode::Periodic)]
                                 << ", rotational " << sc[static_cast<size_t>(EdgeMode::Rotational)] << ", scar "
                                 << sc[static_cast<size_t>(EdgeMode::Scar)] << "; score " << r.report.quality.score);
  CHECK(r.edge_modes[e] == EdgeMode::Periodic);
  CHECK(r.report.quality.flips == 0);
  CHECK(r.report.quality.boundary_intersections == 0);
  CHECK(r.report.quality.angle_max < 1 + 1e-8);
  CHECK(r.report.quality.area_max < 1e-8);
}
