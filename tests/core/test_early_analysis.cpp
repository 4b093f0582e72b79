// The symbolic analysis run ahead of K's values (early_analysis.hpp): the boundary operator's
// pattern foreseen without the coefficients, an assembler built on it taking B's values later, and
// a PartitionedKKT analysed from the pattern alone, then factorised without a second analysis, to
// the bits of the analysis made with the values.
#include <doctest/doctest.h>

#include "meshes.hpp"
#include "same_bits.hpp"
#include "wefm/core/method/coefficients.hpp"
#include "wefm/core/solve/early_analysis.hpp"
#include "wefm/core/method/energy.hpp"
#include "wefm/core/method/energy_assembler.hpp"
#include "wefm/core/sys/error.hpp"
#include "wefm/core/linalg/partitioned_kkt.hpp"
#include "wefm/core/mesh/topology.hpp"

using namespace wefm;
using wefm::test::same_bits;
using wefm::test::same_pattern;

namespace {

// A plate with a hole (two loops, so the boundary term couples uses along both).
TriMesh holed_plate() {
  TriMesh m = test::grid(
      40, 30, [](double u, double v) { return Vec3(3.0 * u, 2.0 * v, 0.2 * std::sin(3.0 * u) * v); }, true);
  std::vector<Tri> kept;
  for (const Tri& t : m.triangles) {
    Vec3 c = Vec3::Zero();
    for (Index v : t) c += m.vertices[static_cast<size_t>(v)] / 3.0;
    if ((c.head<2>() - Eigen::Vector2d(1.5, 1.0)).norm() > 0.4) kept.push_back(t);
  }
  m.triangles = kept;
  return m;
}

}  // namespace

TEST_CASE("the boundary operator's pattern is foreseen without the coefficients") {
  const TriMesh mesh = holed_plate();
  const Topology tp = build_topology(mesh, TopologySpec{});
  REQUIRE(tp.loop_uses.size() == 2);
  const Coefficients c = compute_coefficients(mesh, tp, true, 1e-3);
  for (double unwind : {1.0, 0.3}) {
    const SpMatC B = assemble_boundary_operator(mesh, tp, c, 2.5, unwind);
    const SpMatC P = boundary_operator_pattern(mesh, tp, 2.5);
    REQUIRE(B.nonZeros() > 0);
    CHECK(same_pattern(B, P));
  }
  CHECK(boundary_operator_pattern(mesh, tp, 0.0).nonZeros() == 0);
}

TEST_CASE("an assembler built on B's pattern assembles the K of one built on B") {
  const TriMesh mesh = holed_plate();
  const Topology tp = build_topology(mesh, TopologySpec{});
  const Coefficients c = compute_coefficients(mesh, tp, true, 1e-3);
  const SpMatC B = assemble_boundary_operator(mesh, tp, c, 1.0);
  const SpMatC P = boundary_operator_pattern(mesh, tp, 1.0);
  const std::vector<double> w = compute_weights(tp, c, 0.5);
  const std::vector<Complex> sigma = compute_sigma(c, {}, 0.0);
  const SpMatC K = EnergyAssembler(tp, &B).assemble(w, sigma);

  EnergyAssembler early(tp, &P);
  REQUIRE(early.set_boundary(&B));
  CHECK(same_bits(early.assemble(w, sigma), K));

  // Another pattern is refused and changes nothing: without a boundary term, or with a row fewer.
  EnergyAssembler other(tp, &P);
  CHECK_FALSE(other.set_boundary(nullptr));
  SpMatC fewer = B.topRows(B.rows() - 1);
  fewer.makeCompressed();
  CHECK_FALSE(other.set_boundary(&fewer));
  REQUIRE(other.set_boundary(&B));
  CHECK(same_bits(other.assemble(w, sigma), K));
}

TEST_CASE("a factor analysed ahead from the pattern solves to the bits of one analysed with the values") {
  const TriMesh mesh = holed_plate();
  const Topology tp = build_topology(mesh, TopologySpec{});
  const Coefficients c = compute_coefficients(mesh, tp, true, 1e-3);
  const SpMatC B = assemble_boundary_operator(mesh, tp, c, 1.0);
  const SpMatC K = assemble_energy(tp, c, compute_sigma(c, {}, 0.0), 0.5, Residual::PerHalfEdge, &B);
  const Index n = K.rows(), x0 = 0, x1 = n / 2;
  LinearRow pin, vec;
  pin.terms = {{x0, 1.0}};
  vec.terms = {{x1, 1.0}, {x0, -1.0}};
  vec.rhs = 3.0;
  const std::vector<LinearRow> rows{pin, vec};

  PartitionedKKT plain(Backend::Auto);
  plain.set_matrix(K, x0, x1);
  const VectorXc z = plain.solve(rows, nullptr);

  const SpMatC P = boundary_operator_pattern(mesh, tp, 1.0);
  EnergyAssembler pattern(tp, &P);
  PartitionedKKT ahead(Backend::Auto);
  {
    EarlyAnalysis early(pattern, ahead, x0, x1, nullptr);
    early.copied();
    early.wait();
  }
  CHECK(ahead.counters().analyses == 1);
  ahead.set_matrix(K, x0, x1);
  CHECK(ahead.counters().analyses == 1);  // the pattern was K's: no second analysis
  CHECK(ahead.counters().factorizations == 1);
  CHECK(same_bits(ahead.solve(rows, nullptr), z));

  // A matrix of another pattern is analysed again, as without the early analysis.
  PartitionedKKT wrong(Backend::Auto);
  {
    EnergyAssembler no_boundary(tp, nullptr);
    EarlyAnalysis early(no_boundary, wrong, x0, x1, nullptr);
    early.wait();
  }
  wrong.set_matrix(K, x0, x1);
  CHECK(wrong.counters().analyses == 2);
  CHECK(same_bits(wrong.solve(rows, nullptr), z));
}

TEST_CASE("an analysis ahead that fails reports its error where the factor is waited for") {
  const TriMesh mesh = holed_plate();
  const Topology tp = build_topology(mesh, TopologySpec{});
  const SpMatC P = boundary_operator_pattern(mesh, tp, 1.0);
  const EnergyAssembler pattern(tp, &P);
  PartitionedKKT kkt(Backend::Auto);
  kkt.factor().set_memory_limit(1.0, 2.0);  // the rest alone is over the limit
  EarlyAnalysis early(pattern, kkt, 0, 1, nullptr);
  early.copied();
  try {
    early.wait();
    FAIL("no error");
  } catch (const Error& e) {
    CHECK(e.code() == Errc::out_of_memory);
  }
  // Out-of-range split uses fail in the copy, reported by copied() and wait() alike.
  PartitionedKKT bad(Backend::Auto);
  EarlyAnalysis wrong(pattern, bad, 0, tp.use_count, nullptr);
  CHECK_THROWS_AS(wrong.copied(), Error);
  CHECK_THROWS_AS(wrong.wait(), Error);
}
