// Bad input gets its own error and message; the face stays usable.
#include "solve_helpers.hpp"

using namespace wefm;

namespace {

Errc code_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.code();
  }
  return Errc::internal;  // "no error" is a failure in these tests
}

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("invalid meshes are rejected with a precise message") {
  TriMesh m = test::flat_patch(3);
  SUBCASE("NaN coordinate") {
    m.vertices[2][1] = std::nan("");
    CHECK(code_of([&] { validate_mesh(m); }) == Errc::invalid_mesh);
  }
  SUBCASE("index out of range") {
    m.triangles[1][2] = 999;
    CHECK(code_of([&] { validate_mesh(m); }) == Errc::invalid_mesh);
  }
  SUBCASE("repeated vertex") {
    m.triangles[0][1] = m.triangles[0][0];
    CHECK(code_of([&] { validate_mesh(m); }) == Errc::invalid_mesh);
  }
  SUBCASE("duplicate triangle") {
    m.triangles.push_back({m.triangles[0][1], m.triangles[0][2], m.triangles[0][0]});
    CHECK(code_of([&] { validate_mesh(m); }) == Errc::invalid_mesh);
  }
  SUBCASE("inconsistent orientation") {
    std::swap(m.triangles[4][0], m.triangles[4][1]);
    CHECK(code_of([&] { validate_mesh(m); }) == Errc::invalid_mesh);
  }
  SUBCASE("two components") {
    const Index n = static_cast<Index>(m.vertices.size());
    m.vertices.emplace_back(10, 10, 0);
    m.vertices.emplace_back(11, 10, 0);
    m.vertices.emplace_back(10, 11, 0);
    m.triangles.push_back({n, n + 1, n + 2});
    CHECK(code_of([&] { validate_mesh(m); }) == Errc::invalid_mesh);
  }
}

TEST_CASE("non-manifold vertices: every kind of second fan is found, with the first vertex and its fan count") {
  // Two fans of 6 triangles each around vertex 0, apexes of two cones touching: open fans, closed
  // fans, and one of each.
  auto cone = [](TriMesh& m, Index apex, double z, bool closed, bool upward) {
    const Index base = static_cast<Index>(m.vertices.size());
    const double step = std::acos(-1.0) / 3;
    for (int k = 0; k < 6; ++k) m.vertices.emplace_back(std::cos(k * step), std::sin(k * step), z);
    const int last = closed ? 6 : 5;
    for (int k = 0; k < last; ++k) {
      const Index a = base + k, b = base + (k + 1) % 6;
      if (upward) m.triangles.push_back({apex, a, b});
      else m.triangles.push_back({apex, b, a});
    }
  };
  for (bool first_closed : {false, true})
    for (bool second_closed : {false, true}) {
      CAPTURE(first_closed);
      CAPTURE(second_closed);
      TriMesh m;
      m.vertices = {Vec3(0, 0, 0)};
      cone(m, 0, 1, first_closed, true);
      cone(m, 0, -1, second_closed, false);
      // A strip joining the two rims keeps the mesh connected (vertices 1, 2 to 7, 8), so the
      // apex is the only defect.
      m.triangles.push_back({2, 1, 7});
      m.triangles.push_back({2, 7, 8});
      const std::string msg = message_of([&] { validate_mesh(m); });
      CHECK(msg == "non-manifold vertex 0: its triangles form 2 separate fans");
    }
}

TEST_CASE("duplicate triangles are named before any other defect they cause, and without one") {
  SUBCASE("the same orientation: reported instead of the inconsistent edge") {
    TriMesh m = test::flat_patch(3);
    m.triangles.push_back(m.triangles[4]);
    CHECK(message_of([&] { validate_mesh(m); }).rfind("duplicate triangles: triangle 4 ", 0) == 0);
  }
  SUBCASE("reversed, closing on itself: reported instead of the second component") {
    TriMesh m = test::flat_patch(3);
    const Index n = static_cast<Index>(m.vertices.size());
    m.vertices.emplace_back(10, 10, 0);
    m.vertices.emplace_back(11, 10, 0);
    m.vertices.emplace_back(10, 11, 0);
    m.triangles.push_back({n, n + 1, n + 2});
    m.triangles.push_back({n, n + 2, n + 1});
    CHECK(message_of([&] { validate_mesh(m); }).rfind("duplicate triangles", 0) == 0);
  }
  SUBCASE("a mesh of one reversed pair, which no other check rejects") {
    TriMesh m;
    m.vertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
    m.triangles = {{0, 1, 2}, {0, 2, 1}};
    CHECK(message_of([&] { validate_mesh(m); }) ==
          "duplicate triangles: triangle 0 (0, 1, 2) and triangle 1 (0, 2, 1) use the same vertices");
  }
  SUBCASE("a valid mesh passes") {
    const TriMesh m = test::flat_patch(3);
    CHECK(validate_mesh(m).twin.size() == 3 * m.triangles.size());
  }
}

TEST_CASE("a closed surface with no cut is reported") {
  // Octahedron.
  TriMesh m;
  m.vertices = {Vec3(1, 0, 0), Vec3(-1, 0, 0), Vec3(0, 1, 0), Vec3(0, -1, 0), Vec3(0, 0, 1), Vec3(0, 0, -1)};
  m.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  Face f;
  f.set_mesh(m);
  CHECK(code_of([&] { f.solve(nullptr, nullptr); }) == Errc::invalid_topology);
}

TEST_CASE("invalid topologies each return their own error and the face stays usable") {
  std::vector<std::pair<Index, Index>> seam;
  const TriMesh m = test::open_cylinder(8, 2, &seam);
  Face f;
  f.set_mesh(m);
  SUBCASE("seam on a non-edge") {
    f.add_seams({{0, 20}});
    CHECK(code_of([&] { f.topology(); }) == Errc::invalid_topology);
  }
  SUBCASE("edge that does not follow facet edges") {
    f.add_edge({0, 2});
    f.add_loop({{0, false}});
    CHECK(code_of([&] { f.topology(); }) == Errc::invalid_topology);
  }
  SUBCASE("loop that does not close") {
    f.add_edge({0, 1, 2});
    f.add_loop({{0, false}});
    CHECK(code_of([&] { f.topology(); }) == Errc::invalid_topology);
  }
  SUBCASE("repeated edge whose uses run the same way") {
    f.add_edge({0, 8});
    f.add_loop({{0, false}, {0, false}});
    CHECK(code_of([&] { f.topology(); }) == Errc::invalid_topology);
  }
  // Rings of the 8 x 2 cylinder: bottom 0..7, middle 8..15 (interior), top 16..23; the face lies
  // left of 0 -> 1 -> ... -> 7 -> 0 and of 23 -> 22 -> ... -> 16 -> 23.
  const std::vector<Index> bottom = {0, 1, 2, 3, 4, 5, 6, 7, 0}, middle = {8, 9, 10, 11, 12, 13, 14, 15, 8},
                           top = {23, 22, 21, 20, 19, 18, 17, 16, 23};
  SUBCASE("loop that does not bound the face") {
    f.add_edge(middle);
    f.add_loop({{0, false}});
    CHECK(code_of([&] { f.topology(); }) == Errc::invalid_topology);
    CHECK(message_of([&] { f.topology(); }).find("does not bound the face: edge 0 crosses the interior") != std::string::npos);
  }
  SUBCASE("two loops on the same boundary") {
    f.add_edge(bottom);
    f.add_edge(bottom);
    f.add_loop({{0, false}});
    f.add_loop({{1, false}});
    CHECK(code_of([&] { f.topology(); }) == Errc::invalid_topology);
    CHECK(message_of([&] { f.topology(); }).find("loops 0 and 1 describe the same boundary") != std::string::npos);
  }
  SUBCASE("part of the boundary in no loop") {
    f.add_edge(bottom);
    f.add_loop({{0, false}});
    CHECK(code_of([&] { f.topology(); }) == Errc::invalid_topology);
    CHECK(message_of([&] { f.topology(); }).find("belongs to no loop") != std::string::npos);
  }
  SUBCASE("a loop that runs against the face") {
    f.add_edge(bottom);
    f.add_edge(top);
    f.add_loop({{0, true}});
    f.add_loop({{1, false}});
    CHECK(code_of([&] { f.topology(); }) == Errc::invalid_topology);
    CHECK(message_of([&] { f.topology(); }).find("runs the wrong way along edge 0") != std::string::npos);
  }
  // After any of these, clearing the topology makes the face solvable again (seamless annulus).
  f.clear_topology();
  Options o;
  o.s = 0;
  f.set_options(o);
  f.solve(nullptr, nullptr);
  CHECK(f.has_result());
}

TEST_CASE("caller topology: one loop with the seam used twice equals cutting along the seam") {
  std::vector<std::pair<Index, Index>> seam;
  const Index n = 16, rows = 3;
  const TriMesh m = test::open_cylinder(n, rows, &seam);
  // Edges: bottom circle, top circle, seam; loop: seam up, top circle backwards, seam down, bottom.
  std::vector<Index> bottom, top, up;
  for (Index i = 0; i <= n; ++i) bottom.push_back(i % n);
  for (Index i = n; i >= 0; --i) top.push_back(rows * n + (i % n));
  for (Index j = 0; j <= rows; ++j) up.push_back(j * n);
  Face f;
  f.set_mesh(m);
  const Index eb = f.add_edge(bottom), et = f.add_edge(top), es = f.add_edge(up);
  f.add_loop({{eb, false}, {es, false}, {et, false}, {es, true}});
  Options o = test::with_s(0);
  o.default_edge_mode = EdgeMode::Periodic;
  f.set_options(o);
  f.solve(nullptr, nullptr);
  CHECK(f.topology().repeated.size() == 1);
  CHECK(f.result().report.quality.angle_max < 1 + 1e-7);
}

TEST_CASE("contradictory constraints are reported as singular") {
  Face f;
  f.set_mesh(test::flat_patch(4));
  LinearRow a, b;
  a.terms = {{3, 1.0}};
  a.rhs = 0.0;
  b.terms = {{3, 1.0}};
  b.rhs = 1.0;
  f.add_constraint(a);
  f.add_constraint(b);
  CHECK(code_of([&] { f.solve(nullptr, nullptr); }) == Errc::singular);
  f.clear_constraints();
  f.solve(nullptr, nullptr);
  CHECK(f.has_result());
}

TEST_CASE("redundant but consistent constraints are solved (the KKT matrix is singular)") {
  // The same pin twice, and a third row that is the sum of two pins: M has a null space, which
  // partial pivoting cannot take, so the solve must fall back to full pivoting and still hold
  // every row.
  Face f;
  f.set_mesh(test::flat_patch(6));
  LinearRow a, b, sum;
  a.terms = {{0, 1.0}};
  a.rhs = Complex(1, 2);
  b.terms = {{6, 1.0}};
  b.rhs = Complex(3, 2);
  sum.terms = {{0, 1.0}, {6, 1.0}};
  sum.rhs = Complex(4, 4);
  f.add_constraint(a);
  f.add_constraint(a);
  f.add_constraint(b);
  f.add_constraint(sum);
  f.set_options(test::with_s(0));
  f.solve(nullptr, nullptr);
  CHECK(std::abs(f.result().uv[0] - Complex(1, 2)) < 1e-9);
  CHECK(std::abs(f.result().uv[6] - Complex(3, 2)) < 1e-9);
  CHECK(f.result().report.quality.flips == 0);
}

TEST_CASE("two pins fix the layout exactly where the caller put them") {
  Face f;
  f.set_mesh(test::flat_patch(6));
  LinearRow a, b;
  a.terms = {{0, 1.0}};
  a.rhs = Complex(1, 2);
  b.terms = {{6, 1.0}};
  b.rhs = Complex(3, 2);
  f.add_constraint(a);
  f.add_constraint(b);
  Options o;
  o.s = 0;
  f.set_options(o);
  f.solve(nullptr, nullptr);
  CHECK(std::abs(f.result().uv[0] - Complex(1, 2)) < 1e-9);
  CHECK(std::abs(f.result().uv[6] - Complex(3, 2)) < 1e-9);
}
