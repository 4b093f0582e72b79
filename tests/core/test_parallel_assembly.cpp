// Coefficients, assembly and whole solves split over threads give the same bits as one thread, and
// the matrix assembled straight into its pattern is the A^H A + B^H B it replaces.
#include <cmath>
#include <cstring>

#include <doctest/doctest.h>

#include "meshes.hpp"
#include "same_bits.hpp"
#include "solve_helpers.hpp"
#include "wefm/core/method/coefficients.hpp"
#include "wefm/core/solve/early_analysis.hpp"
#include "wefm/core/method/energy.hpp"
#include "wefm/core/linalg/float_supernodal_solve.hpp"
#include "wefm/core/method/quality.hpp"

using namespace wefm;

namespace {

using wefm::test::same_bits;  // and the Coefficients overload below

bool same_bits(const Coefficients& a, const Coefficients& b) {
  return a.length_scale == b.length_scale && same_bits(a.alpha, b.alpha) && same_bits(a.beta, b.beta) &&
         same_bits(a.length, b.length) && same_bits(a.corner_angle, b.corner_angle) && same_bits(a.use_angle, b.use_angle) &&
         same_bits(a.use_area, b.use_area) && same_bits(a.tri_area, b.tri_area) && a.floored == b.floored &&
         a.degenerate_triangles == b.degenerate_triangles;
}

// Faces large enough that 4 threads really split every loop (ranges of >= 16384 elements, blocks
// of 8192 columns): a jittered saddle, and an open cylinder whose seam doubles a generator's uses.
struct Case {
  const char* name;
  TriMesh mesh;
  TopologySpec spec;
};

std::vector<Case> cases() {
  std::vector<Case> out;
  TriMesh saddle = test::grid(
      200, 200, [](double u, double v) { return Vec3(2 * u - 1, 2 * v - 1, 0.5 * ((2 * u - 1) * (2 * u - 1) - (2 * v - 1) * (2 * v - 1))); },
      true);
  out.push_back({"saddle", std::move(saddle), {}});
  TopologySpec seamed;
  TriMesh cyl = test::open_cylinder(256, 160, &seamed.seams);
  out.push_back({"cylinder", std::move(cyl), std::move(seamed)});
  return out;
}

}  // namespace

TEST_CASE("coefficients and assembly are bit-identical for 1 and 4 threads") {
  for (const Case& cs : cases()) {
    CAPTURE(cs.name);
    REQUIRE(cs.mesh.triangles.size() > 4 * 16384);
    const Topology tp = build_topology(cs.mesh, cs.spec);
    REQUIRE(tp.use_count > 4 * 8192);
    const Coefficients c1 = compute_coefficients(cs.mesh, tp, true, 1e-3, 1), c4 = compute_coefficients(cs.mesh, tp, true, 1e-3, 4);
    CHECK(same_bits(c1, c4));
    std::vector<double> rho(c1.alpha.size());
    for (size_t h = 0; h < rho.size(); ++h) rho[h] = 0.8 + 0.4 * static_cast<double>(h % 7) / 7.0;
    const auto sigma1 = compute_sigma(c1, rho, 1.5, 1), sigma4 = compute_sigma(c1, rho, 1.5, 4);
    CHECK(same_bits(sigma1, sigma4));
    CHECK(same_bits(compute_weights(tp, c1, 0.5, 1), compute_weights(tp, c1, 0.5, 4)));
    const SpMatC B = assemble_boundary_operator(cs.mesh, tp, c1, 1.0);
    for (Residual form : {Residual::PerHalfEdge, Residual::PerUse}) {
      CAPTURE(static_cast<int>(form));
      const SpMatC A1 = assemble_surface_operator(tp, c1, sigma1, 0.5, form, 1);
      CHECK(same_bits(A1, assemble_surface_operator(tp, c1, sigma1, 0.5, form, 4)));
      const SpMatC K1 = assemble_energy(A1, &B, 1);
      CHECK(same_bits(K1, assemble_energy(A1, &B, 4)));
      const SpMatC D1 = assemble_energy(tp, c1, sigma1, 0.5, form, &B, 1);
      CHECK(same_bits(D1, assemble_energy(tp, c1, sigma1, 0.5, form, &B, 4)));
    }
  }
}

TEST_CASE("quality figures are bit-identical for 1 and 4 threads") {
  for (const Case& cs : cases()) {
    CAPTURE(cs.name);
    const Topology tp = build_topology(cs.mesh, cs.spec);
    // A layout with every kind of term: the 3D x, y of each use, jittered, with every 97th use
    // thrown far enough to flip its triangles.
    VectorXc z(tp.use_count);
    for (Index u = 0; u < tp.use_count; ++u) {
      const Vec3& p = cs.mesh.vertices[static_cast<size_t>(tp.use_vertex[static_cast<size_t>(u)])];
      const double jitter = 1e-3 * std::sin(1.7 * static_cast<double>(u));
      z[u] = Complex(p.x() + jitter, p.y() + p.z() - jitter);
      if (u % 97 == 0) z[u] += Complex(0.05, -0.03);
    }
    const Quality q1 = evaluate_quality(cs.mesh, tp, z, 1);
    REQUIRE(q1.flips > 0);
    REQUIRE(q1.angle_max > q1.angle_mean);
    const Quality q4 = evaluate_quality(cs.mesh, tp, z, 4);
    CHECK(std::memcmp(&q1, &q4, sizeof(Quality)) == 0);
    CHECK(q4.flips == q1.flips);
  }
}

TEST_CASE("a whole solve through the continuation is bit-identical for 1 and 3 threads") {
  // The analysis run ahead of the coefficients on a thread of its own (early_analysis.hpp), the
  // continuation's linearisation (two halves of the uses), energy passes (fixed blocks), CG
  // products (one row per output) and the float preconditioner's split solves; the factorisation
  // runs on one thread whatever the count. Every factor takes the float path here.
  set_float_factor_min_entries(0);
  for (const Case& cs : cases()) {
    CAPTURE(cs.name);
    Options o = test::with_s(1.0);
    const std::vector<std::pair<Index, Index>>& seams = cs.spec.seams;
    REQUIRE(early_analysis_pays(static_cast<Index>(cs.mesh.vertices.size()), 3));
    REQUIRE_FALSE(early_analysis_pays(static_cast<Index>(cs.mesh.vertices.size()), 1));
    o.threads = 1;
    const FlattenResult one = test::solve(cs.mesh, o, seams);
    CHECK(one.report.quality.flips == 0);
    CHECK(one.report.iterative_iterations > 0);
    for (int threads : {3}) {
      CAPTURE(threads);
      o.threads = threads;
      const FlattenResult more = test::solve(cs.mesh, o, seams);
      REQUIRE(more.uv.size() == one.uv.size());
      CHECK(std::memcmp(more.uv.data(), one.uv.data(), sizeof(Complex) * static_cast<size_t>(one.uv.size())) == 0);
      CHECK(more.report.iterative_iterations == one.report.iterative_iterations);
      // With threads the analysis ran ahead of K's values (early_analysis.hpp), on the pattern
      // foreseen: no analysis more than with one thread.
      CHECK(more.report.counters.analyses == one.report.counters.analyses);
      CHECK(more.report.counters.factorizations == one.report.counters.factorizations);
    }
  }
  set_float_factor_min_entries(kFloatFactorMinEntries);
}

TEST_CASE("K assembled into its pattern equals A^H A + B^H B and is exactly Hermitian") {
  const TriMesh m = test::hemisphere(24, 12);
  for (bool with_seam : {false, true}) {
    CAPTURE(with_seam);
    TopologySpec spec;
    TriMesh mesh = m;
    if (with_seam) mesh = test::open_cylinder(24, 8, &spec.seams);
    const Topology tp = build_topology(mesh, spec);
    const Coefficients c = compute_coefficients(mesh, tp, true, 1e-3);
    std::vector<double> rho(c.alpha.size());
    for (size_t h = 0; h < rho.size(); ++h) rho[h] = 0.7 + 0.05 * static_cast<double>(h % 11);
    const auto sigma = compute_sigma(c, rho, 1.0);
    const SpMatC B = assemble_boundary_operator(mesh, tp, c, 2.0);
    const SpMatC A = assemble_surface_operator(tp, c, sigma, 0.5, Residual::PerHalfEdge);
    // Reference: Eigen's own product and sum.
    SpMatC ref = SpMatC(A.adjoint()) * A;
    ref += SpMatC(B.adjoint()) * B;
    const SpMatC K = assemble_energy(tp, c, sigma, 0.5, Residual::PerHalfEdge, &B);
    CHECK((K - ref).norm() <= 1e-14 * ref.norm());
    CHECK((assemble_energy(A, &B) - ref).norm() <= 1e-14 * ref.norm());
    CHECK((SpMatC(K.adjoint()) - K).norm() == 0.0);
    // Without a boundary term the pattern is the one-ring of the uses.
    const SpMatC K0 = assemble_energy(tp, c, sigma, 0.5, Residual::PerHalfEdge, nullptr);
    CHECK((K0 - SpMatC(SpMatC(A.adjoint()) * A)).norm() <= 1e-14 * K0.norm());
  }
}
