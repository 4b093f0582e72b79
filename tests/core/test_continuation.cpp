// Continuation in s (METHOD §3, §7; issue "Full WEFM"): developable faces stay exact at every s,
// and on curved faces s trades angle distortion for area distortion monotonically.
#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>
#include <string>

#include "solve_helpers.hpp"

using namespace wefm;

TEST_CASE("developable faces stay exact at s = 0.3, 1 and 2, with and without the boundary term") {
  struct Case {
    std::string name;
    TriMesh mesh;
  };
  // Unjittered grids: moving vertices of a cylinder or cone off the rulings makes the facets
  // non-developable (vertex angle sums leave 2 pi).
  const TriMesh cone = test::grid(24, 8, [](double u, double v) {
    const double t = 0.3 + 0.7 * v, a = 2 * kPi * 0.95 * u;
    return Vec3(0.6 * t * std::cos(a), 0.6 * t * std::sin(a), t);
  });
  const Case cases[] = {{"flat patch", test::flat_patch()}, {"cut cylinder", test::cut_open_cylinder(24, 6)}, {"cut cone", cone}};
  for (const Case& c : cases)
    for (double s : {0.3, 1.0, 2.0})
      for (double mu : {0.0, 1.0}) {
        CAPTURE(c.name);
        CAPTURE(s);
        CAPTURE(mu);
        const auto r = test::solve(c.mesh, test::with_s(s, mu));
        CHECK(r.report.converged);
        CHECK(r.report.s == doctest::Approx(s));
        CHECK(r.report.quality.flips == 0);
        CHECK(r.report.quality.angle_max < 1 + 1e-7);
        CHECK(r.report.quality.area_max < 1e-7);
      }
}

TEST_CASE("on curved faces area distortion falls and angle distortion rises from s = 0 to 1 to 2") {
  struct Case {
    std::string name;
    TriMesh mesh;
  };
  const Case cases[] = {{"hemisphere", test::hemisphere()}, {"saddle", test::saddle()}};
  for (const Case& c : cases) {
    double area_prev = 1e300, angle_prev = 0;
    for (double s : {0.0, 1.0, 2.0}) {
      const auto r = test::solve(c.mesh, test::with_s(s));
      const Quality& q = r.report.quality;
      MESSAGE(c.name << " s=" << s << " area distortion mean " << q.area_mean << " angle distortion mean " << q.angle_mean
                     << " score " << q.score);
      CAPTURE(c.name);
      CAPTURE(s);
      CHECK(r.report.converged);
      CHECK(q.flips == 0);
      CHECK(q.area_mean < area_prev);
      CHECK(q.angle_mean > angle_prev);
      area_prev = q.area_mean;
      angle_prev = q.angle_mean;
    }
  }
}

TEST_CASE("at s = 2 the UV area of the hemisphere is within 2% of its 3D area") {
  const auto r = test::solve(test::hemisphere(), test::with_s(2.0));
  const double ratio = r.report.quality.uv_area / r.report.quality.area_3d;
  MESSAGE("hemisphere s=2: UV area / 3D area = " << ratio);
  CHECK(r.report.s == 2.0);
  CHECK(std::abs(ratio - 1.0) < 0.02);
}

TEST_CASE("the per-use residual of eq. 7 stays available and exact on developable faces") {
  Options o = test::with_s(1.0);
  o.residual = Residual::PerUse;
  const auto r = test::solve(test::cut_open_cylinder(24, 6), o);
  CHECK(r.report.converged);
  CHECK(r.report.quality.angle_max < 1 + 1e-7);
}

TEST_CASE("a caller's pin holds through the continuation, with and without a seam") {
  for (bool with_seam : {false, true}) {
    CAPTURE(with_seam);
    std::vector<std::pair<Index, Index>> seam;
    Face f;
    f.set_mesh(with_seam ? test::open_cylinder(16, 4, &seam) : test::hemisphere());
    if (with_seam) f.add_seams(seam);
    const Index use = f.topology().loop_uses[0][0];
    LinearRow pin;
    pin.terms = {{use, 1.0}};
    pin.rhs = Complex(3, 4);
    f.add_constraint(pin);
    Options o;
    o.s = 1;
    f.set_options(o);
    f.solve(nullptr, nullptr);
    CHECK(f.result().report.converged);
    CHECK(std::abs(f.result().uv[use] - Complex(3, 4)) < 1e-9);
  }
}

TEST_CASE("a helicoid strip of two turns, whose low-distortion layout coils over itself, comes out valid") {
  // r in [1, 1.5], two turns, pitch 0.2: its sides curve one way for more than a full turn.
  const TriMesh strip = test::helicoid_strip(120, 4, 2.0, 1.0, 1.5, 0.4 * kPi);
  const auto r = test::solve(strip, Options());
  MESSAGE("helicoid strip: score " << r.report.quality.score << ", unwind " << r.report.unwind);
  CHECK(r.report.quality.flips == 0);
  CHECK(r.report.quality.boundary_intersections == 0);
  CHECK(r.report.unwind < 1.0);  // the first layout overlapped: the straightened one was kept
}

TEST_CASE("a helicoid strip that coils over itself comes back valid at the s asked, unwound") {
  // Two turns between radii 1 and 1.8: the inner side is 0.56 of the outer, so the layout curls
  // more than a turn and overlaps its own boundary. The unwinding retries straighten gentle
  // turns; at 120 segments weight 10 is not enough at s = 1 or 2, weight 30 is.
  for (double s : {1.0, 2.0}) {
    CAPTURE(s);
    Face f;
    f.set_mesh(test::helicoid_strip(120, 6));
    f.set_options(test::with_s(s));
    const auto& r = test::solve_allowing_cap(f);
    MESSAGE("helicoid strip at s = " << s << ": score " << r.report.quality.score << ", unwind " << r.report.unwind << " at weight " << r.report.unwind_weight);
    CHECK(r.report.s == doctest::Approx(s));
    CHECK(r.report.quality.flips == 0);
    CHECK(r.report.quality.boundary_intersections == 0);
    CHECK(r.report.unwind < 1.0);
    CHECK(r.report.unwind_weight == doctest::Approx(30.0));
    CHECK(r.report.quality.score > 0.8);
  }
}

namespace {

// RMS over the loops' uses of (UV corner angle - 3D corner angle): the turning-angle error of
// the loops.
double turning_angle_error(Face& f) {
  const TriMesh& m = f.mesh();
  const Topology& tp = f.topology();
  const VectorXc& uv = f.result().uv;
  std::vector<double> a3(static_cast<size_t>(tp.use_count), 0.0), a2(static_cast<size_t>(tp.use_count), 0.0);
  for (size_t t = 0; t < m.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const Index p = m.triangles[t][k], q = m.triangles[t][(k + 1) % 3], r = m.triangles[t][(k + 2) % 3];
      const Vec3 e1 = m.vertices[static_cast<size_t>(q)] - m.vertices[static_cast<size_t>(p)];
      const Vec3 e2 = m.vertices[static_cast<size_t>(r)] - m.vertices[static_cast<size_t>(p)];
      const Index up = tp.corner_use[3 * t + static_cast<size_t>(k)];
      const Index uq = tp.corner_use[3 * t + static_cast<size_t>((k + 1) % 3)];
      const Index ur = tp.corner_use[3 * t + static_cast<size_t>((k + 2) % 3)];
      a3[static_cast<size_t>(up)] += std::atan2(e1.cross(e2).norm(), e1.dot(e2));
      a2[static_cast<size_t>(up)] += std::abs(std::arg((uv[ur] - uv[up]) / (uv[uq] - uv[up])));  // no flips: one orientation
    }
  double sum = 0;
  int count = 0;
  for (Index u = 0; u < tp.use_count; ++u)
    if (tp.use_on_loop[static_cast<size_t>(u)]) {
      const double d = a2[static_cast<size_t>(u)] - a3[static_cast<size_t>(u)];
      sum += d * d;
      ++count;
    }
  return std::sqrt(sum / count);
}

}  // namespace

TEST_CASE("the boundary term lowers the turning-angle error along the loops of a curved strip") {
  struct Case {
    std::string name;
    TriMesh mesh;
  };
  const Case cases[] = {
      {"saddle strip", test::grid(60, 6, [](double u, double v) {
         const double x = 4 * u - 2, y = 0.5 * v - 0.25;
         return Vec3(x, y, 0.5 * (x * x - y * y));
       })},
      {"spherical band", test::grid(60, 6, [](double u, double v) {
         const double th = 3.5 * u, ph = 0.2 + 0.5 * v;
         return Vec3(std::cos(ph) * std::cos(th), std::cos(ph) * std::sin(th), std::sin(ph));
       })},
      {"saddle", test::saddle()},
  };
  for (const Case& c : cases)
    for (Residual form : {Residual::PerHalfEdge, Residual::PerUse})
    for (double s : {0.0, 1.0}) {
      double prev = 1e300;
      for (double mu : {0.0, 1.0, 10.0}) {
        Face f;
        f.set_mesh(c.mesh);
        Options o = test::with_s(s, mu);
        o.residual = form;
        f.set_options(o);
        f.solve(nullptr, nullptr);
        const FlattenResult& r = f.result();
        const double err = turning_angle_error(f);
        const std::string label = c.name + (form == Residual::PerUse ? " (eq. 7 per use)" : "");
        MESSAGE(label << " s=" << s << " mu=" << mu << ": turning-angle error (rms, rad) " << err << ", score " << r.report.quality.score);
        CAPTURE(c.name);
        CAPTURE(s);
        CAPTURE(mu);
        CHECK(r.report.quality.flips == 0);
        CHECK(err < prev);
        prev = err;
      }
    }
}

TEST_CASE("a step below the target s ends at 10x rho_tolerance and leaves the target's minimum as it was") {
  // The step to s = 1 only places the start of the step to 2: loosening it must not move the
  // layout the continuation ends in. The reference converges the way up 100x tighter.
  const TriMesh faces[] = {test::hemisphere(), test::saddle()};
  int ended_loose = 0;  // way-up steps that stopped above rho_tolerance: the looser test is in use
  for (const TriMesh& m : faces) {
    Options o = test::with_s(2.0);
    o.s_step = 1.0;  // by default these smooth faces go to s = 2 in one step (test_tentative_step.cpp)
    const auto r = test::solve(m, o);
    Options tight = o;
    tight.rho_tolerance = o.rho_tolerance / 100;
    const auto ref = test::solve(m, tight);
    REQUIRE(r.steps.size() == 2);
    REQUIRE(ref.steps.size() == 2);
    MESSAGE("s = 1 step: " << r.steps[0].iterations << " iterations, rho change " << r.steps[0].rho_change << " (tight: "
                           << ref.steps[0].iterations << ", " << ref.steps[0].rho_change << "); score " << r.report.quality.score
                           << " against " << ref.report.quality.score);
    CHECK(r.steps[0].s == 1.0);
    CHECK(r.steps[0].converged);
    CHECK(r.steps[0].rho_change < 10 * o.rho_tolerance);
    CHECK(r.steps[1].converged);
    CHECK(r.steps[0].iterations <= ref.steps[0].iterations);
    CHECK(r.report.quality.flips == 0);
    CHECK(r.report.quality.score == doctest::Approx(ref.report.quality.score).epsilon(1e-4));
    CHECK(r.report.quality.area_mean == doctest::Approx(ref.report.quality.area_mean).epsilon(1e-2));
    if (r.steps[0].rho_change >= o.rho_tolerance) ++ended_loose;
  }
  CHECK(ended_loose > 0);
}
