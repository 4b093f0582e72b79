// The continuation's tentative step: from s = 0 straight to a target above 1, kept only where every
// Gauss-Newton step on the way is a full one, otherwise taken again in steps of 1.
#include "closed_meshes.hpp"
#include "solve_helpers.hpp"

using namespace wefm;

namespace {

// A unit sphere with the triangles around one vertex removed: a small hole (the face on which
// jumping from s = 0 to 2 cuts its first Gauss-Newton step at the flip bound).
TriMesh sphere_with_small_hole(int levels) {
  const TriMesh s = test::icosphere(levels);
  TriMesh t;
  std::vector<Index> to(s.vertices.size(), -1);
  for (const Tri& f : s.triangles) {
    if (f[0] == 0 || f[1] == 0 || f[2] == 0) continue;
    Tri g;
    for (int k = 0; k < 3; ++k) {
      Index& n = to[static_cast<size_t>(f[k])];
      if (n < 0) {
        n = static_cast<Index>(t.vertices.size());
        t.vertices.push_back(s.vertices[static_cast<size_t>(f[k])]);
      }
      g[k] = n;
    }
    t.triangles.push_back(g);
  }
  return t;
}

Options at_s2(double s_step) {
  Options o = test::with_s(2.0);
  o.s_step = s_step;
  return o;
}

}  // namespace

TEST_CASE("on smooth faces s = 2 is reached in one step, to the layout of steps of 1, in fewer iterations") {
  struct Case {
    const char* name;
    TriMesh mesh;
  };
  const Case cases[] = {{"hemisphere", test::hemisphere()}, {"saddle", test::saddle()}};
  for (const Case& c : cases) {
    CAPTURE(std::string(c.name));
    CHECK(Options().s_step == 2.0);  // the default
    const auto jump = test::solve(c.mesh, at_s2(2.0));
    const auto steps = test::solve(c.mesh, at_s2(1.0));
    MESSAGE(c.name << ": " << jump.report.rho_iterations << " Gauss-Newton iterations in one step against "
                   << steps.report.rho_iterations << " in steps of 1; scores " << jump.report.quality.score << ", "
                   << steps.report.quality.score);
    CHECK(jump.report.abandoned_steps == 0);
    REQUIRE(jump.steps.size() == 1);
    CHECK(jump.steps[0].s == 2.0);
    CHECK(jump.report.converged);
    CHECK(jump.report.quality.flips == 0);
    CHECK(jump.report.quality.boundary_intersections == 0);
    CHECK(std::abs(jump.report.quality.score - steps.report.quality.score) < 1e-4);
    CHECK(jump.report.rho_iterations < steps.report.rho_iterations);
  }
}

TEST_CASE("where Gauss-Newton cuts the step to s = 2 short, it is taken again in steps of 1, to their very layout") {
  const TriMesh m = sphere_with_small_hole(2);
  const auto jump = test::solve(m, at_s2(2.0));
  const auto steps = test::solve(m, at_s2(1.0));
  CHECK(jump.report.abandoned_steps == 1);
  CHECK(steps.report.abandoned_steps == 0);
  REQUIRE(jump.steps.size() == 2);
  CHECK(jump.steps[0].s == 1.0);
  CHECK(jump.steps[1].s == 2.0);
  // Started again from the s = 0 layout with the iteration's state as it was there: the same bits.
  CHECK(jump.uv == steps.uv);
  CHECK(jump.report.quality.score == steps.report.quality.score);
  CHECK(jump.report.quality.flips == 0);
  // The abandoned iterations are counted.
  CHECK(jump.report.rho_iterations > steps.report.rho_iterations);
  CHECK(jump.report.rho_iterations == jump.steps[0].iterations + jump.steps[1].iterations + (jump.report.rho_iterations - steps.report.rho_iterations));
}

TEST_CASE("steps of at most 1 are never tentative") {
  const TriMesh m = sphere_with_small_hole(2);
  for (double st : {1.0, 0.5}) {
    CAPTURE(st);
    const auto r = test::solve(m, at_s2(st));
    CHECK(r.report.abandoned_steps == 0);
    CHECK(r.steps.size() == static_cast<size_t>(std::lround(2.0 / st)));
  }
}
