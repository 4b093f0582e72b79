// Rigid motions, uniform scaling and renumbering change the output only by a similarity.
#include <Eigen/Geometry>

#include "solve_helpers.hpp"
#include "wefm/core/method/coefficients.hpp"

using namespace wefm;

namespace {

// Max deviation of b from the best similarity image of a, relative to a's size.
double similarity_residual(const VectorXc& a, const VectorXc& b) {
  const Complex ca = a.mean(), cb = b.mean();
  const VectorXc x = a.array() - ca, y = b.array() - cb;
  const Complex k = x.dot(y) / x.squaredNorm();  // conj(x).y / |x|^2
  return (y - k * x).cwiseAbs().maxCoeff() / x.cwiseAbs().maxCoeff() / std::abs(k);
}

}  // namespace

TEST_CASE("rigid motion and uniform scaling change the layout only by a similarity") {
  const TriMesh m = test::hemisphere(16, 8);
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  for (double s : {0.0, 1.0}) {
    CAPTURE(s);
    // s > 0 stops the rho fixed point at rho_tolerance, so results agree to that order.
    const double tol = s == 0 ? 1e-7 : 1e-4;
    const auto a = test::solve(m, test::with_s(s));
    const auto b = test::solve(test::transformed(m, R, Vec3(5, -3, 2), 7.5), test::with_s(s));
    CHECK(similarity_residual(a.uv, b.uv) < tol);
    // Lengths follow the input's unit.
    CHECK(b.report.quality.uv_area / a.report.quality.uv_area == doctest::Approx(7.5 * 7.5).epsilon(tol));
  }
}

TEST_CASE("renumbering vertices and triangles changes nothing") {
  const TriMesh m = test::saddle(10);
  TriMesh p = m;
  const Index nv = static_cast<Index>(m.vertices.size());
  std::vector<Index> perm(static_cast<size_t>(nv));
  for (Index i = 0; i < nv; ++i) perm[static_cast<size_t>(i)] = (i * 37 + 11) % nv;  // 37 coprime to 121
  for (Index i = 0; i < nv; ++i) p.vertices[static_cast<size_t>(perm[static_cast<size_t>(i)])] = m.vertices[static_cast<size_t>(i)];
  p.triangles.clear();
  for (size_t t = m.triangles.size(); t-- > 0;) {
    const Tri& f = m.triangles[t];
    p.triangles.push_back({perm[static_cast<size_t>(f[1])], perm[static_cast<size_t>(f[2])], perm[static_cast<size_t>(f[0])]});
  }
  const auto a = test::solve(m, test::with_s(1));
  const auto b = test::solve(p, test::with_s(1));
  // Compare per vertex (no seams, so one use per vertex).
  Face fa, fb;
  fa.set_mesh(m);
  fb.set_mesh(p);
  VectorXc ua(nv), ub(nv);
  for (Index u = 0; u < nv; ++u) ua[fa.topology().use_vertex[static_cast<size_t>(u)]] = a.uv[u];
  for (Index u = 0; u < nv; ++u) ub[fb.topology().use_vertex[static_cast<size_t>(u)]] = b.uv[u];
  VectorXc ub_in_a(nv);
  for (Index i = 0; i < nv; ++i) ub_in_a[i] = ub[perm[static_cast<size_t>(i)]];
  CHECK(similarity_residual(ua, ub_in_a) < 1e-6);
}

TEST_CASE("the translation gauge holds") {
  const TriMesh m = test::saddle(10);
  Face f;
  f.set_mesh(m);
  f.solve(nullptr, nullptr);
  const Coefficients c = compute_coefficients(m, f.topology(), true, 1e-3);
  Complex sum{0, 0};
  double w = 0;
  for (Index u = 0; u < f.topology().use_count; ++u) {
    sum += c.use_area[static_cast<size_t>(u)] * f.result().uv[u];
    w += c.use_area[static_cast<size_t>(u)];
  }
  CHECK(std::abs(sum / w) < 1e-10);
}
