// Curved faces: no flips, and the figures the closing notes quote.
#include <cmath>

#include "solve_helpers.hpp"

using namespace wefm;

TEST_CASE("a hemisphere-like cap and a saddle flatten with no flips and a high score") {
  for (double s : {0.0, 1.0}) {
    CAPTURE(s);
    const auto h = test::solve(test::hemisphere(), test::with_s(s));
    const auto d = test::solve(test::saddle(), test::with_s(s));
    MESSAGE("s=" << s << " cap score " << h.report.quality.score << " saddle score " << d.report.quality.score);
    CHECK(h.report.quality.flips == 0);
    CHECK(d.report.quality.flips == 0);
    CHECK(h.report.quality.boundary_intersections == 0);
    CHECK(d.report.quality.boundary_intersections == 0);
    CHECK(h.report.quality.score > 0.9);
    CHECK(d.report.quality.score > 0.8);
  }
}

TEST_CASE("a disk with three holes flattens with every loop simple and no boundary intersection") {
  const TriMesh m = test::disk_with_holes();
  Face f;
  f.set_mesh(m);
  f.solve(nullptr, nullptr);
  CHECK(f.topology().loops.size() == 4);
  CHECK(f.result().report.quality.boundary_intersections == 0);
  CHECK(f.result().report.quality.flips == 0);
}

TEST_CASE("the two-step gauge costs exactly one numeric factorisation at s = 0") {
  const auto r = test::solve(test::saddle(), test::with_s(0));
  CHECK(r.report.counters.factorizations == 1);
  CHECK(r.report.counters.analyses == 1);
}

TEST_CASE("continuation analyses the pattern once whatever the number of steps") {
  // One analysis in all, for 1 or 8 steps: the continuation refactorises the s = 0 factor in place
  // with the complex-linear part of its Gauss-Newton matrices.
  for (double step : {1.0, 0.125}) {
    Options o = test::with_s(1);
    o.s_step = step;
    const auto r = test::solve(test::hemisphere(), o);
    CAPTURE(step);
    CHECK(r.report.converged);
    CHECK(r.report.counters.analyses == 1);
    // Later Gauss-Newton steps reuse an earlier factorisation as a preconditioner: at most one
    // factorisation per iteration, usually far fewer, and conjugate-gradient iterations show it.
    CHECK(r.report.counters.factorizations >= 2);
    CHECK(r.report.counters.factorizations <= 1 + r.report.rho_iterations);
    CHECK(r.report.iterative_iterations > 0);
    MESSAGE("s_step " << step << ": " << r.report.rho_iterations << " Gauss-Newton iterations, " << r.report.counters.factorizations
                      << " factorisations, " << r.report.iterative_iterations << " PCG iterations");
    CHECK(r.steps.size() == static_cast<size_t>(std::lround(1.0 / step)));
  }
}

TEST_CASE("with substituted seams the continuation analyses its own pattern once") {
  // Periodic seams are substituted (z_a = c z_b + q): the reduced unknowns have another pattern,
  // analysed once whatever the number of steps.
  for (double step : {1.0, 0.25}) {
    std::vector<std::pair<Index, Index>> seam;
    Options o = test::with_s(1);
    o.s_step = step;
    const auto r = test::solve(test::open_cylinder(24, 5, &seam), o, seam, EdgeMode::Periodic);
    CAPTURE(step);
    CHECK(r.report.converged);
    CHECK(r.report.counters.analyses == 2);
    CHECK(r.steps.size() == static_cast<size_t>(std::lround(1.0 / step)));
  }
}

TEST_CASE("testing seam candidates costs one factorisation in all") {
  std::vector<std::pair<Index, Index>> seam;
  const auto r = test::solve(test::open_cylinder(24, 5, &seam), test::with_s(0), seam, EdgeMode::Auto);
  CHECK(r.report.counters.factorizations == 1);
}
