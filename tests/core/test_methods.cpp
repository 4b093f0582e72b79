// The two solver builds, the roll-out method and the boundary term on a two-loop face.
#include <algorithm>
#include <cmath>

#include "solve_helpers.hpp"
#include "wefm/core/linalg/sparse_cholesky.hpp"

using namespace wefm;

namespace {

double max_rel_diff(const VectorXc& a, const VectorXc& b) {
  return (a - b).cwiseAbs().maxCoeff() / std::max(a.cwiseAbs().maxCoeff(), 1e-300);
}

// Signed area of a loop's UV polygon (counter-clockwise > 0).
double loop_area(const Topology& tp, const VectorXc& z, Index loop) {
  const auto& lu = tp.loop_uses[static_cast<size_t>(loop)];
  double a = 0;
  for (size_t j = 0; j < lu.size(); ++j) {
    const Complex p = z[lu[j]], q = z[lu[(j + 1) % lu.size()]];
    a += 0.5 * (p.real() * q.imag() - p.imag() * q.real());
  }
  return a;
}

}  // namespace

TEST_CASE("CHOLMOD and Eigen's own Cholesky give the same layout to 1e-9") {
  if (!have_cholmod()) return;  // the permissive build has only one solver
  for (double s : {0.0, 1.0}) {
    CAPTURE(s);
    Options a = test::with_s(s), b = test::with_s(s);
    a.backend = Backend::Cholmod;
    b.backend = Backend::Eigen;
    const auto ra = test::solve(test::saddle(), a);
    const auto rb = test::solve(test::saddle(), b);
    const double d = max_rel_diff(ra.uv, rb.uv);
    MESSAGE("s=" << s << ": max relative UV difference CHOLMOD vs Eigen " << d);
    CHECK(d < 1e-9);
  }
}

TEST_CASE("the roll-out reproduces the global s = 1 layout on a developable face") {
  Options g = test::with_s(1.0), r = test::with_s(1.0);
  r.method = Method::Rollout;
  const TriMesh m = test::cut_open_cylinder(24, 6);
  const auto rg = test::solve(m, g);
  const auto rr = test::solve(m, r);
  CHECK(rr.report.converged);
  CHECK(rr.report.quality.flips == 0);
  CHECK(rr.report.quality.angle_max < 1 + 1e-6);
  CHECK(rr.report.quality.area_max < 1e-6);
  // Same shape: equal up to a rigid motion, so compare edge lengths of every triangle.
  Face f;
  f.set_mesh(m);
  const Topology& tp = f.topology();
  double worst = 0;
  for (size_t h = 0; h < tp.corner_use.size(); ++h) {
    const size_t n = h - h % 3 + (h % 3 + 1) % 3;
    const double lg = std::abs(rg.uv[tp.corner_use[n]] - rg.uv[tp.corner_use[h]]);
    const double lr = std::abs(rr.uv[tp.corner_use[n]] - rr.uv[tp.corner_use[h]]);
    worst = std::max(worst, std::abs(lg - lr) / lg);
  }
  MESSAGE("roll-out vs global, worst relative edge-length difference: " << worst);
  CHECK(worst < 1e-6);
}

TEST_CASE("the roll-out reports the s it ran at") {
  // The roll-out weighs each prediction by rho^s at the requested s (no continuation), so the
  // report's s is that value, not the global method's default.
  const TriMesh m = test::cut_open_cylinder(24, 6);
  for (double s : {0.0, 0.3, 2.0}) {
    CAPTURE(s);
    Options r = test::with_s(s);
    r.method = Method::Rollout;
    const auto rr = test::solve(m, r);
    CHECK(rr.report.s == s);
  }
}

TEST_CASE("an open cylinder with no cut (an annulus) is determinate with the boundary term: loops simple and nested") {
  const TriMesh m = test::open_cylinder(24, 6);
  // At s = 0, where the boundary term is what makes the system determinate. Both loops are
  // geodesics of the cylinder (3D goals turning 0): before the boundary goals were made to close
  // (+-2 pi per loop) the term folded the inner loop into a segment of zero area.
  Face f;
  f.set_mesh(m);
  f.set_options(test::with_s(0.0));
  f.solve(nullptr, nullptr);
  const auto& r = f.result();
  const Topology& tp = f.topology();
  REQUIRE(tp.loops.size() == 2);
  CHECK(r.report.quality.flips == 0);
  CHECK(r.report.quality.boundary_intersections == 0);
  const Index outer = tp.outer_loop, inner = 1 - tp.outer_loop;
  CHECK(loop_area(tp, r.uv, outer) > 0);  // counter-clockwise
  CHECK(loop_area(tp, r.uv, inner) < 0);  // clockwise
  CHECK(std::abs(loop_area(tp, r.uv, inner)) < loop_area(tp, r.uv, outer));
  CHECK(std::abs(loop_area(tp, r.uv, inner)) > 0.01 * loop_area(tp, r.uv, outer));  // not folded flat
  // Nested: every inner-loop point lies inside the outer polygon (winding number 1).
  const auto& lo = tp.loop_uses[static_cast<size_t>(outer)];
  for (Index u : tp.loop_uses[static_cast<size_t>(inner)]) {
    double wind = 0;
    for (size_t j = 0; j < lo.size(); ++j) wind += std::arg((r.uv[lo[(j + 1) % lo.size()]] - r.uv[u]) / (r.uv[lo[j]] - r.uv[u]));
    CHECK(std::abs(wind / (2 * kPi) - 1.0) < 1e-6);
  }
}

TEST_CASE("the uncut open cylinder at s = 1 comes back valid at s = 1, through s = 2") {
  // Climbing straight to s = 1 its loops cross (the continuation fell back to the s = 0 layout);
  // the retry jumps to s = 2, where the layout stays valid, and steps back down in halves, each
  // step converging (a path that never ends on a cap does not hang on rounding from one CPU's
  // BLAS kernels to another's).
  const TriMesh m = test::open_cylinder(48, 12);
  Face f;
  f.set_mesh(m);
  f.set_options(test::with_s(1.0));
  const auto& r = test::solve_allowing_cap(f);
  MESSAGE("uncut cylinder at s = 1: score " << r.report.quality.score << ", s reached " << r.report.s << ", via s " << r.report.via_s);
  CHECK(r.report.s == doctest::Approx(1.0));
  CHECK(r.report.via_s == doctest::Approx(2.0));
  CHECK(r.report.quality.flips == 0);
  CHECK(r.report.quality.boundary_intersections == 0);
  REQUIRE(r.steps.size() >= 3);
  for (size_t j = r.steps.size() - 3; j < r.steps.size(); ++j) CHECK(r.steps[j].converged);
}

TEST_CASE("roll-out sweeps that diverge to overflow end unconverged with a finite layout") {
  // A three-sided tube, one corner moved 1e134 away (a fuzzer's find): the placement is finite,
  // the Gauss-Seidel sweeps overflow within three. The layout kept must be finite and the solve
  // must say it did not converge, never return infinities or NaN as a result.
  TriMesh m;
  const double c = std::cos(2 * M_PI / 3), s = std::sin(2 * M_PI / 3);
  for (int j = 0; j < 4; ++j) {
    m.vertices.push_back({1, 0, 0.5 * j});
    m.vertices.push_back({c, s, 0.5 * j});
    m.vertices.push_back({c, -s, 0.5 * j});
  }
  m.vertices[0] = {1, 5.6875, 0};
  m.vertices[1].x() = -3.1638862116397002e+134;
  for (Index j = 0; j < 3; ++j)
    for (Index i = 0; i < 3; ++i) {
      const Index a = 3 * j + i, b = 3 * j + (i + 1) % 3;
      m.triangles.push_back({a, b, b + 3});
      m.triangles.push_back({a, b + 3, a + 3});
    }
  Options o = test::with_s(0.0);
  o.method = Method::Rollout;
  o.auto_cut = true;
  o.max_rollout_sweeps = 200;
  Face f;
  f.set_mesh(m);
  f.set_options(o);
  try {
    f.solve(nullptr, nullptr);
    FAIL("the sweeps converged");
  } catch (const Error& e) {
    CHECK(e.code() == Errc::not_converged);
    CHECK(std::string(e.what()).find("diverged") != std::string::npos);
  }
  REQUIRE(f.has_result());
  CHECK(f.result().uv.allFinite());
  CHECK(f.result().report.iterative_iterations < o.max_rollout_sweeps);
}
