// PartitionedKKT: an unrefined solve refined later (a repeated edge's mode candidate ranked first,
// refined only if it may win) gives the bits of a refined solve, and holds its constraints.
#include <doctest/doctest.h>

#include "meshes.hpp"
#include "same_bits.hpp"
#include "wefm/core/method/coefficients.hpp"
#include "wefm/core/method/energy.hpp"
#include "wefm/core/linalg/partitioned_kkt.hpp"
#include "wefm/core/mesh/topology.hpp"

using namespace wefm;
using wefm::test::same_bits;

TEST_CASE("refining an unrefined solve later gives the refined solve's bits") {
  // A curved, jittered strip of skinny triangles (a CAD tessellation's), so that K_PP is badly
  // conditioned and refinement has work to do.
  const TriMesh mesh = test::grid(
      120, 12, [](double u, double v) { return Vec3(40.0 * u, std::cos(3.0 * u) * v, std::sin(3.0 * u) * v + 0.3 * u * u); }, true);
  const Topology tp = build_topology(mesh, TopologySpec{});
  const Coefficients c = compute_coefficients(mesh, tp, true, 1e-3);
  const std::vector<double> rho(c.alpha.size(), 1.0);
  const SpMatC K = assemble_energy(tp, c, compute_sigma(c, rho, 0.0), 0.5, Residual::PerHalfEdge, nullptr);
  const Index n = K.rows();
  REQUIRE(n > 100);

  PartitionedKKT kkt(Backend::Auto);
  kkt.set_matrix(K, 0, n / 2);
  // Two pins and a row tying three uses (as a periodic seam ties two sides and a shift).
  LinearRow a, b, tie;
  a.terms = {{3, 1.0}};
  a.rhs = Complex(0.25, -1.0);
  b.terms = {{n - 5, 1.0}};
  b.rhs = Complex(2.0, 0.5);
  tie.terms = {{7, 1.0}, {n / 3, -1.0}, {n / 2, Complex(0.0, 0.5)}};
  tie.rhs = Complex(0.1, 0.2);
  const std::vector<LinearRow> rows = {a, b, tie};
  // A dense row (the centroid held, as the translation gauge does) makes the reduced system
  // ill-conditioned: the unrefined solve is off by more than rounding and refinement takes rounds.
  const Eigen::VectorXd eta = Eigen::VectorXd::Constant(n, 1.0 / static_cast<double>(n));

  (void)kkt.solve_unrefined(rows, &eta);  // caches the columns of the rows' uses
  auto solves = [&] { return kkt.counters().solves; };
  const auto s0 = solves();
  const VectorXc refined = kkt.solve(rows, &eta);
  const auto s1 = solves();
  PartitionedKKT::Unrefined first = kkt.solve_unrefined(rows, &eta);
  const auto s2 = solves();
  REQUIRE(first.z.size() == n);
  REQUIRE(first.lambda.size() == 4);
  const VectorXc unrefined = first.z;
  // Another candidate's solve in between: the kept start does not depend on what ran since.
  (void)kkt.solve_unrefined({a}, &eta);
  const auto s3 = solves();
  const VectorXc later = kkt.refine(rows, &eta, std::move(first));
  const auto s4 = solves();
  CHECK(same_bits(later, refined));
  // Continuing costs the refinement rounds only: together with the unrefined solve, exactly the
  // solves of one refined solve.
  CHECK(s2 - s1 >= 1);
  CHECK(s4 - s3 >= 2);
  CHECK((s2 - s1) + (s4 - s3) == s1 - s0);

  for (const VectorXc* z : {&unrefined, &refined}) {
    for (const LinearRow& r : rows) {
      Complex lhs{0, 0};
      for (auto& [u, g] : r.terms) lhs += g * (*z)[u];
      CHECK(std::abs(lhs - r.rhs) < 1e-9);
    }
    CHECK(std::abs(eta.cast<Complex>().dot(*z)) < 1e-9);
  }
  // Refinement did change the layout (else the bit comparison above would prove nothing), by
  // rounding only.
  CHECK(!same_bits(unrefined, refined));
  CHECK((unrefined - refined).norm() <= 1e-6 * refined.norm());
}
