// The Gauss-Newton steps' conjugate gradients deflate the layout's rotation (gauss_newton.cpp,
// solve_step): a change of preconditioner only, so the layout is the same to the continuation's
// tolerance, and where the rotation's small Rayleigh quotient set the count, CG takes fewer
// iterations.
#include <algorithm>
#include <cmath>

#include "solve_helpers.hpp"
#include "wefm/core/solve/gauss_newton.hpp"

using namespace wefm;

namespace {

// Restores the process-wide switch however the test ends.
struct Deflation {
  explicit Deflation(bool on) { set_rotation_deflation(on); }
  ~Deflation() { set_rotation_deflation(true); }
};

double extent(const VectorXc& uv) {
  double lo_x = 1e300, hi_x = -1e300, lo_y = 1e300, hi_y = -1e300;
  for (Index i = 0; i < uv.size(); ++i) {
    lo_x = std::min(lo_x, uv[i].real());
    hi_x = std::max(hi_x, uv[i].real());
    lo_y = std::min(lo_y, uv[i].imag());
    hi_y = std::max(hi_y, uv[i].imag());
  }
  return std::max(hi_x - lo_x, hi_y - lo_y);
}

FlattenResult solve_with(bool deflate, const TriMesh& m, const Options& o, const std::vector<std::pair<Index, Index>>& seams = {}) {
  const Deflation d(deflate);
  return test::solve(m, o, seams);
}

}  // namespace

TEST_CASE("deflating the rotation gives the same layout to the continuation's tolerance in fewer CG iterations") {
  CHECK(rotation_deflation());  // on by default
  // Curved faces where the rotation's Rayleigh quotient sets CG's count: a bowl with three holes
  // (four loops, like the benchmark's plate) and a hemisphere.
  TriMesh bowl = test::disk_with_holes();
  for (Vec3& p : bowl.vertices) p.z() = 0.5 * (p.x() * p.x() + p.y() * p.y());
  const TriMesh faces[] = {bowl, test::hemisphere(40, 20)};
  for (const TriMesh& m : faces)
    for (double s : {1.0, 2.0}) {
      CAPTURE(m.triangles.size());
      CAPTURE(s);
      const Options o = test::with_s(s);
      const FlattenResult off = solve_with(false, m, o);
      const FlattenResult on = solve_with(true, m, o);
      REQUIRE(on.uv.size() == off.uv.size());
      CHECK(on.report.converged);
      CHECK(on.report.quality.flips == 0);
      CHECK(on.report.quality.boundary_intersections == 0);
      const double moved = (on.uv - off.uv).cwiseAbs().maxCoeff() / extent(off.uv);
      MESSAGE(m.triangles.size() << " triangles, s = " << s << ": CG iterations " << off.report.iterative_iterations << " -> "
                                 << on.report.iterative_iterations << ", Gauss-Newton " << off.report.rho_iterations << " -> "
                                 << on.report.rho_iterations << ", largest move " << moved << " of the extent, score "
                                 << off.report.quality.score << " -> " << on.report.quality.score);
      // Both stop at the rho tolerance (1e-3), possibly one Gauss-Newton iteration apart.
      CHECK(moved < 1e-4);
      CHECK(std::abs(on.report.quality.score - off.report.quality.score) < 1e-5);
      CHECK(on.report.rho_iterations <= off.report.rho_iterations);
      CHECK(on.report.iterative_iterations < off.report.iterative_iterations);
    }
}

// A caller's pin under the deflated preconditioner: test_continuation.cpp ("a caller's pin holds").
TEST_CASE("deflating the rotation over substituted seams gives the same layout") {
  std::vector<std::pair<Index, Index>> seam;
  const TriMesh cylinder = test::open_cylinder(24, 8, &seam);
  const Options o = test::with_s(1.0);
  const FlattenResult off = solve_with(false, cylinder, o, seam);
  const FlattenResult on = solve_with(true, cylinder, o, seam);
  REQUIRE(on.uv.size() == off.uv.size());
  CHECK(on.report.converged);
  CHECK(on.report.quality.flips == 0);
  CHECK((on.uv - off.uv).cwiseAbs().maxCoeff() / extent(off.uv) < 1e-5);
}
