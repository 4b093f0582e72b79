// Free meshing (METHOD §9): constrained Delaunay + refinement + improvement judged in 3D.
#include <algorithm>
#include <map>
#include <vector>

#include "mesh_faces.hpp"

using namespace wefm;

namespace {

// Mean 3D edge length of a triangle mesh.
double mean_edge(const meshing::DomainMesh& dm) {
  double s = 0;
  for (size_t e = 0; e < dm.elements.size(); e += 3)
    for (size_t k = 0; k < 3; ++k) s += (dm.xyz[static_cast<size_t>(dm.elements[e + k])] - dm.xyz[static_cast<size_t>(dm.elements[e + (k + 1) % 3])]).norm();
  return s / static_cast<double>(dm.elements.size());
}

}  // namespace

TEST_CASE("free meshing of a flat disk with holes gives min lambda >= 0.6 and keeps the holes") {
  const auto f = test::solved(test::disk_with_holes());
  meshing::MeshOptions o;
  o.size = 0.06;
  const auto dm = f.mesh_domain(o);
  MESSAGE("disk with holes: ", dm.report.elements, " triangles, lambda_mesh ", dm.report.lambda_mesh, ", min ", dm.report.lambda_min);
  CHECK(dm.report.lambda_min >= 0.6);
  CHECK(dm.report.lambda_mesh >= 0.9);
  CHECK(dm.report.outside_nodes == 0);
  CHECK(test::max_off_surface(f.mesh(), dm) <= 1e-9);
  CHECK(mean_edge(dm) == doctest::Approx(o.size).epsilon(0.25));
  // Area of the mesh equals the face's: the holes stay empty and nothing outside is meshed.
  double a3 = 0, am = 0;
  for (size_t t = 0; t < f.mesh().triangles.size(); ++t) a3 += triangle_area(f.mesh(), static_cast<Index>(t));
  for (size_t e = 0; e < dm.elements.size(); e += 3)
    am += 0.5 * (dm.xyz[static_cast<size_t>(dm.elements[e + 1])] - dm.xyz[static_cast<size_t>(dm.elements[e])])
                    .cross(dm.xyz[static_cast<size_t>(dm.elements[e + 2])] - dm.xyz[static_cast<size_t>(dm.elements[e])]).norm();
  CHECK(am == doctest::Approx(a3).epsilon(1e-9));
}

TEST_CASE("free meshing of a curved face puts every node on the 3D triangulation at size near h") {
  const auto f = test::solved(test::saddle(24), 1.0);
  meshing::MeshOptions o;
  o.size = 0.08;
  const auto dm = f.mesh_domain(o);
  MESSAGE("saddle: ", dm.report.elements, " triangles, lambda_mesh ", dm.report.lambda_mesh, ", min ", dm.report.lambda_min);
  CHECK(test::max_off_surface(f.mesh(), dm) <= 1e-9);
  CHECK(dm.report.lambda_mesh >= 0.9);
  CHECK(dm.report.lambda_min >= 0.5);
  CHECK(mean_edge(dm) == doctest::Approx(o.size).epsilon(0.25));
}

TEST_CASE("free meshing of a cylinder with a periodic seam: node counts match across the seam") {
  std::vector<std::pair<Index, Index>> seam;
  const TriMesh m = test::open_cylinder(32, 8, &seam);
  const auto f = test::solved(m, 0.0, seam, EdgeMode::Periodic);
  meshing::MeshOptions o;
  o.size = 0.17;
  const auto dm = f.mesh_domain(o);
  CHECK(dm.report.lambda_min >= 0.6);
  CHECK(test::max_off_surface(f.mesh(), dm) <= 1e-9);
  // Seam nodes (angle 0) come from both sides: each 3D point exactly twice, at distinct UV.
  std::map<long, std::vector<Index>> by_height;
  for (Index k = 0; k < static_cast<Index>(dm.xyz.size()); ++k) {
    const Vec3& x = dm.xyz[static_cast<size_t>(k)];
    if (std::fabs(x.y()) < 1e-12 && x.x() > 0) by_height[std::lround(x.z() * 1e9)].push_back(k);
  }
  CHECK(by_height.size() >= 10);
  for (const auto& [z, ks] : by_height) {
    CAPTURE(z);
    REQUIRE(ks.size() == 2);
    CHECK((dm.uv[static_cast<size_t>(ks[0])] - dm.uv[static_cast<size_t>(ks[1])]).norm() > 1.0);
  }
}

TEST_CASE("caller-given edge nodes become the boundary nodes") {
  const auto f = test::solved(test::unit_square(4));
  const Topology& tp = f.topo();
  REQUIRE(tp.edges.size() == 1);
  // The square's only edge: give nodes on its first side (y = 0) at uneven spacing.
  meshing::EdgeNodes given;
  given[0] = {Vec3(0.1, 0, 0), Vec3(0.15, 0, 0), Vec3(0.6, 0, 0), Vec3(1, 0.5, 0), Vec3(0.3, 1, 0), Vec3(0, 0.5, 0)};
  meshing::MeshOptions o;
  o.size = 0.2;
  const auto dm = f.mesh_domain(o, given);
  int found = 0;
  for (const Vec3& g : given[0])
    for (const Vec3& x : dm.xyz) found += x == g ? 1 : 0;  // bit for bit: faces sharing the edge share its nodes
  CHECK(found == 6);
  CHECK(dm.boundary_nodes == 6 + 4);  // the given nodes and the edge's end and corner vertices
}

TEST_CASE("mesh options are checked") {
  const auto f = test::solved(test::unit_square(4));
  meshing::MeshOptions o;
  o.size = 0;
  CHECK_THROWS_AS(f.mesh_domain(o), Error);
  o.size = 0.1;
  o.min_angle_deg = 50;
  CHECK_THROWS_AS(f.mesh_domain(o), Error);
  o.min_angle_deg = 28;
  o.max_elements = 10;
  CHECK_THROWS_AS(f.mesh_domain(o), Error);
}

TEST_CASE("a raised cancel flag stops free meshing with Error(cancelled)") {
  const auto f = test::solved(test::unit_square(4));
  meshing::MeshOptions o;
  o.size = 0.01;
  const std::atomic<bool> cancel{true};
  try {
    (void)meshing::mesh_domain(f.mesh(), f.topo(), f.uv(), o, {}, meshing::MeshControl{&cancel, {}});
    FAIL("not cancelled");
  } catch (const Error& e) {
    CHECK(e.code() == Errc::cancelled);
  }
}

TEST_CASE("meshing reports its progress from 0 to 1, and a progress callback returning false stops it") {
  const auto f = test::solved(test::unit_square(4));
  meshing::MeshOptions o;
  o.size = 0.02;  // a few thousand triangles: several insertion reports
  std::vector<double> seen;
  meshing::MeshControl control;
  control.progress = [&](double x) {
    seen.push_back(x);
    return true;
  };
  const auto dm = meshing::mesh_domain(f.mesh(), f.topo(), f.uv(), o, {}, control);
  REQUIRE(seen.size() >= 5);
  CHECK(seen.front() == 0.0);
  CHECK(seen.back() == 1.0);
  CHECK(std::is_sorted(seen.begin(), seen.end()));
  CHECK(std::count_if(seen.begin(), seen.end(), [](double x) { return x > 0.1 && x < 0.8 + 1e-12; }) >= 2);
  CHECK(dm.elements.size() / 3 > 1000);

  int calls = 0;
  control.progress = [&](double) { return ++calls < 3; };
  try {
    (void)meshing::mesh_domain(f.mesh(), f.topo(), f.uv(), o, {}, control);
    FAIL("not stopped");
  } catch (const Error& e) {
    CHECK(e.code() == Errc::cancelled);
    CHECK(calls == 3);
  }
}

TEST_CASE("improvement reports its passes, and a stop asked for during improvement ends meshing there") {
  // The improvement passes over a face of millions of triangles take seconds each: a stop must be
  // heard between them, not only once the whole face is done.
  const auto f = test::solved(test::unit_square(4));
  meshing::MeshOptions o;
  o.size = 0.02;
  std::vector<double> seen;
  meshing::MeshControl control;
  control.progress = [&](double x) {
    seen.push_back(x);
    return true;
  };
  (void)meshing::mesh_domain(f.mesh(), f.topo(), f.uv(), o, {}, control);
  auto improving = [](double x) { return x > 0.8 && x < 0.95; };
  REQUIRE(std::count_if(seen.begin(), seen.end(), improving) >= 3);

  seen.clear();
  control.progress = [&](double x) {
    seen.push_back(x);
    return !improving(x);
  };
  try {
    (void)meshing::mesh_domain(f.mesh(), f.topo(), f.uv(), o, {}, control);
    FAIL("not stopped");
  } catch (const Error& e) {
    CHECK(e.code() == Errc::cancelled);
    REQUIRE(!seen.empty());
    CHECK(improving(seen.back()));
    CHECK(std::count_if(seen.begin(), seen.end(), improving) == 1);
  }
}

TEST_CASE("no mesh edge spans a half tube narrower than the size: edges between boundary nodes follow the surface") {
  // A half tube of radius 2 and length 20 meshed at size 4: as wide as the tube is across, so the
  // mesher joins its two straight edges by chords through the axis, where a half model's symmetry
  // plane (another face) lies. Split where the surface bulges from them by more than a quarter of
  // their length, every edge subtends at most about 106 degrees of the arc, and its middle stays
  // 0.6 r or more from the axis (the ends' single arc segments excepted: they are the boundary).
  const auto f = test::solved(test::cut_cylinder(12, 40, 2.0, 20.0, kPi));
  meshing::MeshOptions o;
  o.size = 4.0;
  const auto dm = f.mesh_domain(o);
  REQUIRE(dm.elements.size() >= 6);
  double nearest = 1e300;
  for (size_t t = 0; t + 2 < dm.elements.size(); t += 3)
    for (size_t i = 0; i < 3; ++i) {
      const Vec3 m = 0.5 * (dm.xyz[static_cast<size_t>(dm.elements[t + i])] + dm.xyz[static_cast<size_t>(dm.elements[t + (i + 1) % 3])]);
      if (m.z() > 1e-9 && m.z() < 20 - 1e-9) nearest = std::min(nearest, std::hypot(m.x(), m.y()));
    }
  CHECK(nearest >= 0.55 * 2.0);
  CHECK(test::max_off_surface(f.mesh(), dm) <= 1e-9);
}

TEST_CASE("split_chords: a coarse half tube's chords between boundary nodes are split, however short") {
  // The half tube above at size 10: its diameter (4) is under half the size, so by default the
  // mesher keeps chords through the axis (a corner's or a cusp's span, as far as it can tell). A
  // caller whose other face shares those two boundary nodes (the tube's other half, a symmetry
  // plane) asks for them to be split: every edge then keeps its middle off the axis.
  const auto f = test::solved(test::cut_cylinder(12, 40, 2.0, 20.0, kPi));
  auto nearest_to_axis = [&](const meshing::DomainMesh& dm) {
    double nearest = 1e300;
    for (size_t t = 0; t + 2 < dm.elements.size(); t += 3)
      for (size_t i = 0; i < 3; ++i) {
        const Vec3 m = 0.5 * (dm.xyz[static_cast<size_t>(dm.elements[t + i])] + dm.xyz[static_cast<size_t>(dm.elements[t + (i + 1) % 3])]);
        if (m.z() > 1e-9 && m.z() < 20 - 1e-9) nearest = std::min(nearest, std::hypot(m.x(), m.y()));
      }
    return nearest;
  };
  meshing::MeshOptions o;
  o.size = 10.0;
  const auto plain = f.mesh_domain(o);
  CHECK(nearest_to_axis(plain) < 0.5 * 2.0);
  o.split_chords = true;
  const auto split = f.mesh_domain(o);
  CHECK(nearest_to_axis(split) >= 0.6 * 2.0);
  CHECK(split.xyz.size() > plain.xyz.size());
  CHECK(test::max_off_surface(f.mesh(), split) <= 1e-9);
}
