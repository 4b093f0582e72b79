// Every bad-input class of tests/README.md through the C API: its status, a message that names the
// culprit, the face left as it was, and the caller's arrays untouched.
#include <doctest/doctest.h>

#include <cstring>
#include <limits>

#include "capi_meshes.hpp"

using namespace wefm_test;

namespace {

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// A face holding a valid 4x4 flat mesh; every bad call below must leave that mesh in place.
struct Fixture {
  Arrays good = flat(4);
  Face face{good};
  int64_t uses = 0;
  Fixture() {
    REQUIRE(face.last == WEFM_OK);
    uses = use_count(face);
    REQUIRE(uses == good.nv());
  }
  wefm_status set(const Arrays& a) { return wefm_face_set_mesh(face, a.nv(), a.xyz.data(), a.nt(), a.tri.data()); }
  void check_unchanged() {
    CHECK(use_count(face) == uses);
    CHECK(wefm_face_solve(face) == WEFM_OK);
  }
};

}  // namespace

TEST_CASE("mesh: NaN or infinite coordinates are rejected naming the vertex") {
  Fixture fx;
  for (double bad : {std::nan(""), std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()}) {
    Arrays a = flat(4);
    a.xyz[3 * 7 + 2] = bad;
    CHECK(fx.set(a) == WEFM_ERROR_INVALID_MESH);
    CHECK(contains(fx.face.error(), "vertex 7 "));
    CHECK(contains(fx.face.error(), "NaN or infinite"));
  }
  fx.check_unchanged();
}

TEST_CASE("mesh: out-of-range and negative indices are rejected naming the triangle") {
  Fixture fx;
  Arrays a = flat(4);
  a.tri[3 * 5 + 1] = static_cast<int32_t>(a.nv());
  CHECK(fx.set(a) == WEFM_ERROR_INVALID_MESH);
  CHECK(contains(fx.face.error(), "triangle 5"));
  CHECK(contains(fx.face.error(), "out of range"));
  a = flat(4);
  a.tri[3 * 2] = -1;
  CHECK(fx.set(a) == WEFM_ERROR_INVALID_MESH);
  CHECK(contains(fx.face.error(), "triangle 2"));
  CHECK(contains(fx.face.error(), "-1"));
  // The 64-bit entry point: values beyond int32 are out of range, not truncated.
  std::vector<int64_t> t64(a.tri.begin(), a.tri.end());
  t64[0] = int64_t(1) << 32;  // would alias vertex 0 if truncated
  CHECK(wefm_face_set_mesh_i64(fx.face, a.nv(), a.xyz.data(), a.nt(), t64.data()) == WEFM_ERROR_INVALID_MESH);
  CHECK(contains(fx.face.error(), "4294967296"));
  // Mesh handles made from arrays: the same check, status OUT_OF_RANGE (wefm_mesh_create's contract).
  wefm_mesh* m = reinterpret_cast<wefm_mesh*>(&fx);
  CHECK(wefm_mesh_create(a.nv(), a.xyz.data(), a.nt(), a.tri.data(), &m) == WEFM_ERROR_OUT_OF_RANGE);
  CHECK(m == nullptr);
  CHECK(contains(wefm_last_error(), "-1"));
  fx.check_unchanged();
}

TEST_CASE("mesh: negative or too large counts, too few elements and NULL arrays") {
  Fixture fx;
  const Arrays& g = fx.good;
  CHECK(wefm_face_set_mesh(fx.face, -1, g.xyz.data(), g.nt(), g.tri.data()) == WEFM_ERROR_INVALID_ARGUMENT);
  CHECK(wefm_face_set_mesh(fx.face, g.nv(), g.xyz.data(), -3, g.tri.data()) == WEFM_ERROR_INVALID_ARGUMENT);
  CHECK(wefm_face_set_mesh(fx.face, int64_t(1) << 31, g.xyz.data(), g.nt(), g.tri.data()) == WEFM_ERROR_INVALID_MESH);
  CHECK(wefm_face_set_mesh(fx.face, g.nv(), g.xyz.data(), 0, g.tri.data()) == WEFM_ERROR_INVALID_MESH);
  CHECK(contains(fx.face.error(), "at least 3 vertices and 1 triangle"));
  CHECK(wefm_face_set_mesh(fx.face, g.nv(), nullptr, g.nt(), g.tri.data()) == WEFM_ERROR_NULL_ARGUMENT);
  CHECK(wefm_face_set_mesh(fx.face, g.nv(), g.xyz.data(), g.nt(), nullptr) == WEFM_ERROR_NULL_ARGUMENT);
  CHECK(wefm_face_set_mesh(nullptr, g.nv(), g.xyz.data(), g.nt(), g.tri.data()) == WEFM_ERROR_NULL_ARGUMENT);
  fx.check_unchanged();
}

TEST_CASE("mesh: a triangle repeating a vertex is rejected") {
  Fixture fx;
  Arrays a = flat(4);
  a.tri[3 * 9 + 2] = a.tri[3 * 9];
  CHECK(fx.set(a) == WEFM_ERROR_INVALID_MESH);
  CHECK(contains(fx.face.error(), "triangle 9"));
  CHECK(contains(fx.face.error(), "repeats a vertex"));
  fx.check_unchanged();
}

TEST_CASE("mesh: duplicate triangles are rejected (either orientation)") {
  Fixture fx;
  Arrays a = flat(4);
  a.add_tri(a.tri[4], a.tri[5], a.tri[3]);  // triangle 1 again, rotated
  CHECK(fx.set(a) == WEFM_ERROR_INVALID_MESH);
  CHECK(contains(fx.face.error(), "duplicate triangles"));
  CHECK(contains(fx.face.error(), "triangle 1 "));
  a = flat(4);
  a.add_tri(a.tri[3], a.tri[5], a.tri[4]);  // reversed: a two-sided sliver
  CHECK(fx.set(a) == WEFM_ERROR_INVALID_MESH);
  CHECK(contains(fx.face.error(), "duplicate triangles"));
  fx.check_unchanged();
}

TEST_CASE("mesh: non-manifold edges and vertices are rejected") {
  Fixture fx;
  SUBCASE("edge shared by three triangles") {
    Arrays a = flat(4);
    // A fin on the interior diagonal of triangle 0 (its corners 0 and 2), shared with triangle 1.
    a.add_vertex(0.3, 0.1, 1.0);
    a.add_tri(a.tri[0], a.tri[2], static_cast<int32_t>(a.nv() - 1));
    CHECK(fx.set(a) == WEFM_ERROR_INVALID_MESH);
    CHECK(contains(fx.face.error(), "non-manifold edge"));
  }
  SUBCASE("two fans meeting at one vertex (bow tie)") {
    Arrays a;
    a.xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0, -1, 0, 0, 0, -1, 0};
    a.tri = {0, 1, 2, 0, 3, 4};
    CHECK(fx.set(a) == WEFM_ERROR_INVALID_MESH);
    CHECK(contains(fx.face.error(), "non-manifold vertex 0"));
  }
  fx.check_unchanged();
}

TEST_CASE("mesh: inconsistent orientation is rejected naming both triangles") {
  Fixture fx;
  Arrays a = flat(4);
  std::swap(a.tri[3 * 6], a.tri[3 * 6 + 1]);
  CHECK(fx.set(a) == WEFM_ERROR_INVALID_MESH);
  CHECK(contains(fx.face.error(), "inconsistent triangle orientation"));
  CHECK(contains(fx.face.error(), "6"));
  fx.check_unchanged();
}

TEST_CASE("mesh: several connected components are rejected") {
  Fixture fx;
  Arrays a = flat(4);
  const int32_t n = static_cast<int32_t>(a.nv());
  a.add_vertex(10, 10, 0);
  a.add_vertex(11, 10, 0);
  a.add_vertex(10, 11, 0);
  a.add_tri(n, n + 1, n + 2);
  CHECK(fx.set(a) == WEFM_ERROR_INVALID_MESH);
  CHECK(contains(fx.face.error(), "several connected components"));
  CHECK(contains(fx.face.error(), "triangle 32"));
  fx.check_unchanged();
}

TEST_CASE("mesh: unreferenced vertices are accepted and get no use") {
  Arrays a = flat(4);
  a.add_vertex(5, 5, 5);
  Face f(a);
  CHECK(f.last == WEFM_OK);
  CHECK(use_count(f) == a.nv() - 1);
  CHECK(wefm_face_solve(f) == WEFM_OK);
  CHECK(all_finite(get_uv(f)));
}

TEST_CASE("mesh: zero-area triangles are repaired (min_beta), counted, and the layout is valid") {
  // A flat 4x4 grid whose middle row is squashed onto the row below: the triangles between them
  // have zero area but the face stays a valid disk.
  Arrays a = flat(4);
  for (int i = 0; i <= 4; ++i) a.xyz[3 * (2 * 5 + i) + 1] = a.xyz[3 * (1 * 5 + i) + 1];
  Face f(a);
  REQUIRE(f.last == WEFM_OK);
  wefm_options o = options();
  o.s = 0;
  REQUIRE(wefm_face_set_options(f, &o) == WEFM_OK);
  CHECK(wefm_face_solve(f) == WEFM_OK);
  const wefm_report r = report_of(f);
  CHECK(r.degenerate_triangles == 8);
  CHECK(all_finite(get_uv(f)));
  // wefm_mesh_info counts them too, so a caller can see them before flattening.
  wefm_mesh* m = nullptr;
  REQUIRE(wefm_mesh_create(a.nv(), a.xyz.data(), a.nt(), a.tri.data(), &m) == WEFM_OK);
  wefm_mesh_info info;
  wefm_mesh_info_init(&info);
  CHECK(wefm_mesh_get_info(m, &info) == WEFM_OK);
  CHECK(info.degenerate_triangles == 8);
  wefm_mesh_release(m);
}

TEST_CASE("mesh: a face whose triangles are all degenerate fails cleanly") {
  Arrays a;
  a.xyz = {0, 0, 0, 1, 0, 0, 2, 0, 0, 3, 0, 0};
  a.tri = {0, 1, 2, 2, 1, 3};
  Face f(a);
  if (f.last == WEFM_OK) {
    const wefm_status s = wefm_face_solve(f);
    INFO(std::string(wefm_status_string(s)), ": ", f.error());
    CHECK(s != WEFM_OK);
    CHECK(s != WEFM_ERROR_INTERNAL);
    int32_t solved = 1;
    wefm_face_has_result(f, &solved);
    CHECK(solved == 0);
  } else {
    CHECK(f.last == WEFM_ERROR_INVALID_MESH);
  }
}

TEST_CASE("mesh: coordinates too large or too small for double are INVALID_MESH saying so") {
  // Edge lengths squared overflow (1e200) or underflow (1e-200): the triangles measured zero area
  // and the message said there was no shape, where the shape was there and the scale was the fault.
  // The same mesh at 1e100 and 1e-100 is well within range and flattens.
  for (double scale : {1e200, 1e-200, 1e100, 1e-100}) {
    const bool in_range = scale == 1e100 || scale == 1e-100;
    Arrays a = flat(3);
    for (double& x : a.xyz) x *= scale;
    Face f(a);
    REQUIRE(f.last == WEFM_OK);
    if (in_range) {
      CHECK(wefm_face_solve(f) == WEFM_OK);
    } else {
      CHECK(wefm_face_solve(f) == WEFM_ERROR_INVALID_MESH);
      CHECK(contains(f.error(), "rescale the coordinates"));
    }
  }
}

TEST_CASE("topology: a closed surface with no cut is INVALID_TOPOLOGY; seams fix it") {
  const Arrays a = octahedron();
  Face f(a);
  REQUIRE(f.last == WEFM_OK);
  wefm_options o = options();
  o.s = 0;  // conformal: the cut octahedron is far from developable; the point here is the topology
  REQUIRE(wefm_face_set_options(f, &o) == WEFM_OK);
  CHECK(wefm_face_solve(f) == WEFM_ERROR_INVALID_TOPOLOGY);
  CHECK(contains(f.error(), "closed surface"));
  CHECK(contains(f.error(), "wefm_face_add_seams"));
  CHECK(contains(f.error(), "auto_cut"));  // the message offers the automatic cut too
  // auto_cut slits it through its six corners (120 degree cones): the octahedron's net, undistorted.
  o.auto_cut = 1;
  REQUIRE(wefm_face_set_options(f, &o) == WEFM_OK);
  CHECK(wefm_face_solve(f) == WEFM_OK);
  wefm_report r;
  wefm_report_init(&r, sizeof r);
  REQUIRE(wefm_face_get_report(f, &r) == WEFM_OK);
  CHECK(r.auto_cut == 1);
  CHECK(r.auto_cut_edges == 5);
  CHECK(r.flipped_triangles == 0);
  CHECK(r.boundary_intersections == 0);
  CHECK(r.angle_distortion_max < 1 + 1e-9);
  // Switching it off again is a topology change: back to the closed surface, and its error.
  o.auto_cut = 0;
  REQUIRE(wefm_face_set_options(f, &o) == WEFM_OK);
  int32_t solved = 1;
  wefm_face_has_result(f, &solved);
  CHECK(solved == 0);
  CHECK(wefm_face_build(f) == WEFM_ERROR_INVALID_TOPOLOGY);
  int32_t id = -1;
  CHECK(wefm_face_add_pin(f, 0, 0, 0, &id) == WEFM_ERROR_INVALID_TOPOLOGY);  // uses need a topology
  // Cut along a path 4-0-5 through the closed surface: a disk.
  const int32_t seam[] = {4, 0, 0, 5};
  CHECK(wefm_face_add_seams(f, 2, seam) == WEFM_OK);
  CHECK(wefm_face_solve(f) == WEFM_OK);
}

TEST_CASE("topology: loops, edges and seams that do not match the mesh") {
  const Arrays a = open_cylinder(8, 2);
  Face f(a);
  REQUIRE(f.last == WEFM_OK);
  wefm_options o = options();
  o.s = 0;
  REQUIRE(wefm_face_set_options(f, &o) == WEFM_OK);
  int32_t e = -1, l = -1;
  SUBCASE("edge vertex out of range: OUT_OF_RANGE at add time") {
    const int32_t ch[] = {0, 99};
    CHECK(wefm_face_add_edge(f, 2, ch, &e) == WEFM_ERROR_OUT_OF_RANGE);
    CHECK(contains(f.error(), "99"));
  }
  SUBCASE("loop naming an edge that does not exist: OUT_OF_RANGE at add time") {
    const int32_t edges[] = {3};
    CHECK(wefm_face_add_loop(f, 1, edges, nullptr, &l) == WEFM_ERROR_OUT_OF_RANGE);
    CHECK(contains(f.error(), "edge 3"));
  }
  SUBCASE("empty edge or loop: INVALID_ARGUMENT") {
    const int32_t ch[] = {0};
    CHECK(wefm_face_add_edge(f, 0, ch, &e) == WEFM_ERROR_INVALID_ARGUMENT);
    CHECK(wefm_face_add_loop(f, -4, ch, nullptr, &l) == WEFM_ERROR_INVALID_ARGUMENT);
  }
  SUBCASE("edge not along facet edges") {
    const int32_t ch[] = {0, 2};
    REQUIRE(wefm_face_add_edge(f, 2, ch, &e) == WEFM_OK);
    REQUIRE(wefm_face_add_loop(f, 1, &e, nullptr, &l) == WEFM_OK);
    CHECK(wefm_face_build(f) == WEFM_ERROR_INVALID_TOPOLOGY);
    CHECK(contains(f.error(), "does not follow facet edges"));
  }
  SUBCASE("loop that does not close") {
    const int32_t ch[] = {0, 1, 2};
    REQUIRE(wefm_face_add_edge(f, 3, ch, &e) == WEFM_OK);
    REQUIRE(wefm_face_add_loop(f, 1, &e, nullptr, &l) == WEFM_OK);
    CHECK(wefm_face_solve(f) == WEFM_ERROR_INVALID_TOPOLOGY);
    CHECK(contains(f.error(), "does not close"));
  }
  SUBCASE("loops that leave part of the boundary out") {
    std::vector<int32_t> bottom;
    for (int i = 0; i <= 8; ++i) bottom.push_back(i % 8);
    REQUIRE(wefm_face_add_edge(f, 9, bottom.data(), &e) == WEFM_OK);
    REQUIRE(wefm_face_add_loop(f, 1, &e, nullptr, &l) == WEFM_OK);
    CHECK(wefm_face_build(f) == WEFM_ERROR_INVALID_TOPOLOGY);
    CHECK(contains(f.error(), "belongs to no loop"));
  }
  SUBCASE("seam on vertices not joined by a facet edge") {
    const int32_t pairs[] = {0, 20};
    REQUIRE(wefm_face_add_seams(f, 1, pairs) == WEFM_OK);
    CHECK(wefm_face_build(f) == WEFM_ERROR_INVALID_TOPOLOGY);
    CHECK(contains(f.error(), "seam 0"));
  }
  SUBCASE("seam on a boundary facet edge") {
    const int32_t pairs[] = {0, 1};
    REQUIRE(wefm_face_add_seams(f, 1, pairs) == WEFM_OK);
    CHECK(wefm_face_build(f) == WEFM_ERROR_INVALID_TOPOLOGY);
    CHECK(contains(f.error(), "boundary"));
  }
  SUBCASE("seam vertex out of range: OUT_OF_RANGE at add time") {
    const int32_t pairs[] = {0, -8};
    CHECK(wefm_face_add_seams(f, 1, pairs) == WEFM_ERROR_OUT_OF_RANGE);
  }
  SUBCASE("outer loop that does not exist") {
    CHECK(wefm_face_set_outer_loop(f, -2) == WEFM_ERROR_OUT_OF_RANGE);
    REQUIRE(wefm_face_set_outer_loop(f, 5) == WEFM_OK);  // checked against the loops at build time
    CHECK(wefm_face_build(f) == WEFM_ERROR_INVALID_TOPOLOGY);
    CHECK(contains(f.error(), "outer loop 5"));
  }
  SUBCASE("edge mode out of range or on an unknown edge") {
    CHECK(wefm_face_set_edge_mode(f, 0, 7) == WEFM_ERROR_INVALID_ARGUMENT);
    CHECK(wefm_face_set_edge_mode(f, 40, WEFM_EDGE_FREE) == WEFM_ERROR_OUT_OF_RANGE);
  }
  // After any of these, clearing the topology makes the face solvable again.
  CHECK(wefm_face_clear_topology(f) == WEFM_OK);
  CHECK(wefm_face_solve(f) == WEFM_OK);
}

TEST_CASE("constraints: unknown uses, no terms and non-finite values are INVALID_CONSTRAINT") {
  Fixture fx;
  int32_t id = -1;
  CHECK(wefm_face_add_pin(fx.face, static_cast<int32_t>(fx.uses), 0, 0, &id) == WEFM_ERROR_INVALID_CONSTRAINT);
  CHECK(contains(fx.face.error(), "use " + std::to_string(fx.uses)));
  CHECK(wefm_face_add_pin(fx.face, -1, 0, 0, &id) == WEFM_ERROR_INVALID_CONSTRAINT);
  CHECK(wefm_face_add_pin(fx.face, 0, std::nan(""), 0, &id) == WEFM_ERROR_INVALID_CONSTRAINT);
  const int32_t uses[] = {0, 1};
  const double coef[] = {1, 0, std::numeric_limits<double>::infinity(), 0}, rhs[] = {0, 0};
  CHECK(wefm_face_add_constraint(fx.face, 2, uses, coef, rhs, &id) == WEFM_ERROR_INVALID_CONSTRAINT);
  CHECK(contains(fx.face.error(), "non-finite"));
  CHECK(wefm_face_add_constraint(fx.face, 0, uses, coef, rhs, &id) == WEFM_ERROR_INVALID_CONSTRAINT);
  CHECK(id == -1);
  fx.check_unchanged();
}

TEST_CASE("constraints: contradictory pins make the KKT system singular; the face stays usable") {
  Fixture fx;
  REQUIRE(wefm_face_solve(fx.face) == WEFM_OK);
  const std::vector<double> before = get_uv(fx.face);
  int32_t id;
  // Adding constraints clears the result (documented), so keep a second face for "previous result".
  REQUIRE(wefm_face_add_pin(fx.face, 3, 0, 0, &id) == WEFM_OK);
  REQUIRE(wefm_face_add_pin(fx.face, 3, 1, 0, &id) == WEFM_OK);
  CHECK(wefm_face_solve(fx.face) == WEFM_ERROR_SINGULAR);
  CHECK(contains(fx.face.error(), "contradict"));
  // A linear combination contradicting two pins: z0 - z5 = 1 with z0 = z5 = 0.
  REQUIRE(wefm_face_clear_constraints(fx.face) == WEFM_OK);
  const int32_t uses[] = {0, 5};
  const double coef[] = {1, 0, -1, 0}, rhs[] = {1, 0};
  REQUIRE(wefm_face_add_pin(fx.face, 0, 0, 0, &id) == WEFM_OK);
  REQUIRE(wefm_face_add_pin(fx.face, 5, 0, 0, &id) == WEFM_OK);
  REQUIRE(wefm_face_add_constraint(fx.face, 2, uses, coef, rhs, &id) == WEFM_OK);
  CHECK(wefm_face_solve(fx.face) == WEFM_ERROR_SINGULAR);
  REQUIRE(wefm_face_clear_constraints(fx.face) == WEFM_OK);
  CHECK(wefm_face_solve(fx.face) == WEFM_OK);
  CHECK(get_uv(fx.face) == before);
}

TEST_CASE("constraints: values beyond what double can place are INVALID_CONSTRAINT at solve; tiny coefficients are fine") {
  // Found by the C API fuzzer: a pin at 1.7e308 came back as WEFM_OK with infinite UVs, and one at
  // 1e300 as a layout whose vertices all rounded to the pin.
  Fixture fx;
  REQUIRE(wefm_face_solve(fx.face) == WEFM_OK);
  const std::vector<double> before = get_uv(fx.face);
  int32_t id = -1;
  for (double far : {1.7e308, 1e300, 1e20}) {
    REQUIRE(wefm_face_clear_constraints(fx.face) == WEFM_OK);
    REQUIRE(wefm_face_add_pin(fx.face, 0, far, 0, &id) == WEFM_OK);
    CHECK(wefm_face_solve(fx.face) == WEFM_ERROR_INVALID_CONSTRAINT);
    CHECK(contains(fx.face.error(), "constraint 0"));
    CHECK(contains(fx.face.error(), "edge lengths"));
  }
  // A row whose largest coefficient is tiny reaches as far as its quotient: 1 / 5e-324 overflows.
  const int32_t uses[] = {0, 5};
  const double tiny[] = {5e-324, 0, 0, 0}, one[] = {1, 0};
  REQUIRE(wefm_face_clear_constraints(fx.face) == WEFM_OK);
  REQUIRE(wefm_face_add_constraint(fx.face, 2, uses, tiny, one, &id) == WEFM_OK);
  CHECK(wefm_face_solve(fx.face) == WEFM_ERROR_INVALID_CONSTRAINT);
  // Zero coefficients with a non-zero right-hand side can never hold.
  const double zero[] = {0, 0, 0, 0};
  REQUIRE(wefm_face_clear_constraints(fx.face) == WEFM_OK);
  REQUIRE(wefm_face_add_constraint(fx.face, 2, uses, zero, one, &id) == WEFM_OK);
  CHECK(wefm_face_solve(fx.face) == WEFM_ERROR_INVALID_CONSTRAINT);
  CHECK(contains(fx.face.error(), "zero coefficients"));
  // The same pin written with coefficients of 1e-300 is the same constraint: z0 = (1, 2).
  const double small[] = {1e-300, 0, 0, 0}, small_rhs[] = {1e-300, 2e-300};
  REQUIRE(wefm_face_clear_constraints(fx.face) == WEFM_OK);
  REQUIRE(wefm_face_add_constraint(fx.face, 2, uses, small, small_rhs, &id) == WEFM_OK);
  REQUIRE(wefm_face_solve(fx.face) == WEFM_OK);
  const std::vector<double> uv = get_uv(fx.face);
  CHECK(uv[0] == doctest::Approx(1.0));
  CHECK(uv[1] == doctest::Approx(2.0));
  // A far pin within range keeps its triangles apart: the layout is the pinned one, shifted.
  REQUIRE(wefm_face_clear_constraints(fx.face) == WEFM_OK);
  REQUIRE(wefm_face_add_pin(fx.face, 0, 1e6, 0, &id) == WEFM_OK);
  REQUIRE(wefm_face_solve(fx.face) == WEFM_OK);
  wefm_report r;
  wefm_report_init(&r);
  REQUIRE(wefm_face_get_report(fx.face, &r) == WEFM_OK);
  CHECK(r.flipped_triangles == 0);
  CHECK(r.score > 0.9);
  CHECK(get_uv(fx.face)[0] == doctest::Approx(1e6));
  REQUIRE(wefm_face_clear_constraints(fx.face) == WEFM_OK);
  CHECK(wefm_face_solve(fx.face) == WEFM_OK);
  CHECK(get_uv(fx.face) == before);
}

TEST_CASE("options: every out-of-range value is INVALID_ARGUMENT naming the option; old options kept") {
  Fixture fx;
  wefm_options keep = options();
  keep.s = 0.5;
  REQUIRE(wefm_face_set_options(fx.face, &keep) == WEFM_OK);
  const double nan = std::nan(""), inf = std::numeric_limits<double>::infinity();
  struct Case {
    const char* name;
    std::function<void(wefm_options&)> set;
  };
  const Case cases[] = {
      {"s", [&](wefm_options& o) { o.s = 2.5; }},
      {"s", [&](wefm_options& o) { o.s = nan; }},
      {"s", [&](wefm_options& o) { o.s = -inf; }},
      {"k", [&](wefm_options& o) { o.k = 1.5; }},
      {"boundary_weight", [&](wefm_options& o) { o.boundary_weight = -1; }},
      {"boundary_weight", [&](wefm_options& o) { o.boundary_weight = inf; }},
      {"method", [&](wefm_options& o) { o.method = 9; }},
      {"solver", [&](wefm_options& o) { o.solver = -1; }},
      {"default_edge_mode", [&](wefm_options& o) { o.default_edge_mode = 5; }},
      {"s_step", [&](wefm_options& o) { o.s_step = 0; }},
      {"s_step", [&](wefm_options& o) { o.s_step = nan; }},
      {"s_step", [&](wefm_options& o) { o.s_step = 1e-12; }},  // would take 1e12 continuation steps
      {"rho_tolerance", [&](wefm_options& o) { o.rho_tolerance = 0; }},
      {"max_rho_iterations", [&](wefm_options& o) { o.max_rho_iterations = 0; }},
      {"rollout_tolerance", [&](wefm_options& o) { o.rollout_tolerance = nan; }},
      {"max_rollout_sweeps", [&](wefm_options& o) { o.max_rollout_sweeps = -5; }},
      {"score_threshold", [&](wefm_options& o) { o.score_threshold = nan; }},
      {"threads", [&](wefm_options& o) { o.threads = -1; }},
      {"memory_limit_mb", [&](wefm_options& o) { o.memory_limit_mb = -1; }},
      {"memory_limit_mb", [&](wefm_options& o) { o.memory_limit_mb = nan; }},
      {"min_beta", [&](wefm_options& o) { o.min_beta = 0; }},
      {"min_beta", [&](wefm_options& o) { o.min_beta = 1; }},
  };
  for (const Case& c : cases) {
    wefm_options o = options();
    c.set(o);
    const wefm_status s = wefm_face_set_options(fx.face, &o);
    INFO("option ", c.name, ": ", fx.face.error());
    CHECK(s == WEFM_ERROR_INVALID_ARGUMENT);
    CHECK(contains(fx.face.error(), c.name));
  }
  wefm_options o = options();
  o.struct_size = 0;
  CHECK(wefm_face_set_options(fx.face, &o) == WEFM_ERROR_INVALID_ARGUMENT);
  CHECK(contains(fx.face.error(), "struct_size"));
  wefm_options got = options();
  REQUIRE(wefm_face_get_options(fx.face, &got) == WEFM_OK);
  CHECK(got.s == 0.5);
  fx.check_unchanged();
}

TEST_CASE("queries out of order or out of range") {
  Face f;
  CHECK(wefm_face_solve(f) == WEFM_ERROR_INVALID_STATE);
  int64_t n;
  CHECK(wefm_face_use_count(f, &n) == WEFM_ERROR_INVALID_STATE);
  const Arrays a = flat(3);
  REQUIRE(wefm_face_set_mesh(f, a.nv(), a.xyz.data(), a.nt(), a.tri.data()) == WEFM_OK);
  CHECK(wefm_face_get_uv(f, nullptr, 0, &n) == WEFM_ERROR_INVALID_STATE);
  REQUIRE(wefm_face_solve(f) == WEFM_OK);
  int32_t buf[8];
  CHECK(wefm_face_get_edge(f, -1, buf, 8, &n) == WEFM_ERROR_OUT_OF_RANGE);
  CHECK(wefm_face_get_loop(f, 1 << 30, buf, 8, &n) == WEFM_ERROR_OUT_OF_RANGE);
  CHECK(wefm_face_get_vertex_uses(f, static_cast<int32_t>(a.nv()), buf, 8, &n) == WEFM_ERROR_OUT_OF_RANGE);
  double s[5];
  CHECK(wefm_face_get_edge_scores(f, 3, s, 5, &n) == WEFM_ERROR_OUT_OF_RANGE);
  CHECK(wefm_face_get_uv(f, nullptr, 0, nullptr) == WEFM_ERROR_NULL_ARGUMENT);
}

TEST_CASE("the caller's arrays are never modified") {
  // Every input array is passed const; check that the bytes are the same after each call, whether
  // the call succeeds or fails.
  Arrays a = flat(4);
  a.add_vertex(7, 7, 7);  // unreferenced: accepted
  const Arrays copy = a;
  auto same = [&] { return std::memcmp(a.xyz.data(), copy.xyz.data(), a.xyz.size() * sizeof(double)) == 0 && a.tri == copy.tri; };
  Face f;
  REQUIRE(wefm_face_set_mesh(f, a.nv(), a.xyz.data(), a.nt(), a.tri.data()) == WEFM_OK);
  CHECK(same());
  std::vector<int64_t> t64(a.tri.begin(), a.tri.end());
  const std::vector<int64_t> t64c = t64;
  REQUIRE(wefm_face_set_mesh_i64(f, a.nv(), a.xyz.data(), a.nt(), t64.data()) == WEFM_OK);
  CHECK(t64 == t64c);
  wefm_mesh* m = nullptr;
  REQUIRE(wefm_mesh_create(a.nv(), a.xyz.data(), a.nt(), a.tri.data(), &m) == WEFM_OK);
  CHECK(same());
  wefm_mesh_release(m);
  // A rejected mesh (NaN): still untouched.
  a.xyz[0] = std::nan("");
  Arrays bad = a;
  CHECK(wefm_face_set_mesh(f, a.nv(), a.xyz.data(), a.nt(), a.tri.data()) == WEFM_ERROR_INVALID_MESH);
  CHECK(std::memcmp(a.xyz.data(), bad.xyz.data(), a.xyz.size() * sizeof(double)) == 0);
  a = copy;
  // Topology, seams, constraints, options.
  std::vector<int32_t> bottom{0, 1, 2, 3, 4};
  const std::vector<int32_t> bottom_c = bottom;
  int32_t e;
  REQUIRE(wefm_face_add_edge(f, 5, bottom.data(), &e) == WEFM_OK);
  std::vector<int32_t> edges{e}, rev{0};
  REQUIRE(wefm_face_add_loop(f, 1, edges.data(), rev.data(), nullptr) == WEFM_OK);
  CHECK(bottom == bottom_c);
  CHECK(edges == std::vector<int32_t>{e});
  CHECK(rev == std::vector<int32_t>{0});
  REQUIRE(wefm_face_clear_topology(f) == WEFM_OK);
  std::vector<int32_t> seams{6, 7, 7, 8};
  REQUIRE(wefm_face_add_seams(f, 2, seams.data()) == WEFM_OK);
  CHECK(seams == (std::vector<int32_t>{6, 7, 7, 8}));
  REQUIRE(wefm_face_clear_topology(f) == WEFM_OK);
  std::vector<int32_t> uses{0, 4};
  std::vector<double> coef{1, 0, -1, 0}, rhs{-2, 0};
  const std::vector<double> coef_c = coef, rhs_c = rhs;
  int32_t id;
  REQUIRE(wefm_face_add_constraint(f, 2, uses.data(), coef.data(), rhs.data(), &id) == WEFM_OK);
  CHECK(uses == (std::vector<int32_t>{0, 4}));
  CHECK(coef == coef_c);
  CHECK(rhs == rhs_c);
  wefm_options o = options();
  o.s = 0.75;
  wefm_options oc = o;
  REQUIRE(wefm_face_set_options(f, &o) == WEFM_OK);
  CHECK(std::memcmp(&o, &oc, sizeof o) == 0);
  REQUIRE(wefm_face_solve(f) == WEFM_OK);
  CHECK(same());
  // A short output buffer is not written either.
  int64_t n = 0;
  std::vector<double> small(4, -7.0);
  CHECK(wefm_face_get_uv(f, small.data(), 4, &n) == WEFM_ERROR_BUFFER_TOO_SMALL);
  CHECK(small == std::vector<double>(4, -7.0));
  CHECK(n == 2 * use_count(f));
}
