// The shape barrier of the continuation: zero on layouts that keep the 3D shapes, a residual that
// grows without bound as a triangle degenerates, and a derivative that matches finite differences.
#include <cmath>

#include "solve_helpers.hpp"
#include "wefm/core/method/coefficients.hpp"
#include "wefm/core/method/shape_barrier.hpp"

using namespace wefm;

namespace {

struct OneTriangle {
  TriMesh mesh;
  Topology topo;
  Coefficients coef;
  explicit OneTriangle(const std::array<Vec3, 3>& v) {
    mesh.vertices = {v[0], v[1], v[2]};
    mesh.triangles = {{0, 1, 2}};
    topo = build_topology(mesh, TopologySpec{});
    coef = compute_coefficients(mesh, topo, true, 1e-3);
  }
};

}  // namespace

TEST_CASE("the shape barrier is zero on an undistorted layout and grows without bound as a triangle flattens") {
  const OneTriangle t({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.3, 0.8, 0)});
  const ShapeBarrier b(t.topo, t.coef, 1e-3);
  double r = 0;
  std::array<Complex, 3> l;
  // The 3D shape itself, scaled and turned: the barrier is scale-free and off.
  const Complex rot = 5.0 * std::polar(1.0, 0.7);
  CHECK_FALSE(b.row(0, 0.0, rot * Complex(1, 0), rot * Complex(0.3, 0.8), r, l));
  // The apex sinks towards the base: off until the shape is eps of its 3D shape, then rising.
  double last = -1;
  int active = 0;
  for (double h = 0.8; h > 1e-6; h *= 0.5) {
    if (!b.row(0, 0.0, 1.0, Complex(0.3, h), r, l)) continue;
    ++active;
    CHECK(r > last);
    last = r;
  }
  CHECK(active > 10);
  CHECK(last > 1e3);
  // Flipped: left to the line search.
  CHECK_FALSE(b.row(0, 0.0, 1.0, Complex(0.3, -0.01), r, l));
}

TEST_CASE("the shape barrier's derivative matches central differences") {
  const OneTriangle t({Vec3(0, 0, 0), Vec3(2, 0, 0.1), Vec3(0.7, 1.1, -0.2)});
  const ShapeBarrier b(t.topo, t.coef, 1e-3);
  const std::array<Complex, 3> z = {Complex(0.1, -0.2), Complex(2.3, 0.05), Complex(1.9, 0.04)};  // a squashed layout
  double r = 0;
  std::array<Complex, 3> l;
  REQUIRE(b.row(0, z[0], z[1], z[2], r, l));
  const double step = 1e-7;
  for (int k = 0; k < 3; ++k)
    for (Complex dir : {Complex(1, 0), Complex(0, 1)}) {
      std::array<Complex, 3> zp = z, zm = z;
      zp[static_cast<size_t>(k)] += step * dir;
      zm[static_cast<size_t>(k)] -= step * dir;
      double rp = 0, rm = 0;
      std::array<Complex, 3> unused;
      REQUIRE(b.row(0, zp[0], zp[1], zp[2], rp, unused));
      REQUIRE(b.row(0, zm[0], zm[1], zm[2], rm, unused));
      const double fd = (rp - rm) / (2 * step);
      const double analytic = 2 * (l[static_cast<size_t>(k)] * dir).real();
      CAPTURE(k);
      CAPTURE(dir);
      CHECK(analytic == doctest::Approx(fd).epsilon(1e-5));
    }
}
