// The single-precision copy of the supernodal factor (float_supernodal_solve.hpp) that the
// continuation preconditions with: its solves agree with the double factor's to float precision,
// the fallback keeps the double factor bit for bit, its solve split over the elimination tree gives
// the same bits on any number of threads, and so does a continuation preconditioned by it.
#include <cmath>
#include <cstring>
#include <random>

#include <doctest/doctest.h>
#include "same_bits.hpp"

#include "magnetic_grid.hpp"
#include "solve_helpers.hpp"
#include "wefm/core/linalg/float_supernodal_solve.hpp"
#include "wefm/core/linalg/sparse_cholesky.hpp"

using namespace wefm;
using wefm::test::same_bits;

namespace {

Eigen::MatrixXcd random_rhs(Index n, Index cols) {
  std::mt19937 rng(11);
  std::normal_distribution<double> g;
  Eigen::MatrixXcd b(n, cols);
  for (Index j = 0; j < cols; ++j)
    for (Index i = 0; i < n; ++i) b(i, j) = Complex(g(rng), g(rng));
  return b;
}

// Restores the process-wide switches however the test ends.
struct FloatFactorSettings {
  explicit FloatFactorSettings(std::size_t min_entries, FloatFactorKernels k = FloatFactorKernels::Auto) {
    set_float_factor_min_entries(min_entries);
    set_float_factor_kernels(k);
  }
  ~FloatFactorSettings() {
    set_float_factor_min_entries(kFloatFactorMinEntries);
    set_float_factor_kernels(FloatFactorKernels::Auto);
  }
};

}  // namespace

TEST_CASE("the single-precision factor solves like the double one to float precision") {
  if (!have_cholmod()) {
    MESSAGE("no CHOLMOD in this build: the float factor copies CHOLMOD's supernodal factor");
    return;
  }
  const FloatFactorSettings every_factor(0);
  const SpMatC K = test::magnetic_grid(70, 1e-2);
  const Eigen::MatrixXcd b = random_rhs(K.rows(), 3);
  SparseCholesky exact;
  exact.factorize(K);
  const Eigen::MatrixXcd xd = exact.solve(b);

  SparseCholesky single;
  single.factorize(K);
  const bool kept = single.keep_single_precision();
  CHECK(kept == float_factor_kernels_available());
  CHECK(single.single_precision() == kept);
  if (!kept) {
    MESSAGE("this CPU has no AVX2 + FMA (or WEFM_FLOAT_FACTOR=0): the double path is all there is");
    CHECK(same_bits(single.solve(b), xd));
    return;
  }
  const Eigen::MatrixXcd xf = single.solve(b);
  for (Index j = 0; j < b.cols(); ++j) {
    CAPTURE(j);
    const double err = (xf.col(j) - xd.col(j)).norm() / xd.col(j).norm();
    const double res = (K * xf.col(j) - b.col(j)).norm() / b.col(j).norm();
    MESSAGE("column " << j << ": relative difference " << err << ", residual " << res);
    CHECK(err < 1e-4);
    CHECK(err > 0);  // really the float factor: double rounding would not differ this much
    CHECK(res < 1e-4);
  }
  // Deterministic, and homogeneous: a residual 2^-200 the size gives the result 2^-200 the size,
  // bit for bit (it is scaled to 1 before it is rounded to float).
  CHECK(same_bits(single.solve(b), xf));
  const double tiny = std::ldexp(1.0, -200);
  CHECK(same_bits(single.solve(b * tiny), xf * tiny));
  // A zero residual gives zero.
  CHECK(single.solve(Eigen::MatrixXcd::Zero(K.rows(), 1)).isZero(0));

  // Refactorised (the double values were freed): back to a double factor of the new values (wefm's
  // own refactorisation: that of a fresh CHOLMOD factorisation to rounding), until the copy is
  // taken again.
  SpMatC K2 = K;
  for (Index i = 0; i < K2.rows(); ++i) K2.coeffRef(i, i) += 0.5;
  single.factorize(K2);
  CHECK(!single.single_precision());
  SparseCholesky exact2;
  exact2.factorize(K2);
  const Eigen::MatrixXcd xd2 = exact2.solve(b);
  CHECK((single.solve(b) - xd2).norm() / xd2.norm() < 1e-12);
  CHECK(single.counters().analyses == 1);
  CHECK(single.keep_single_precision());
  CHECK((single.solve(b) - xd2).norm() / xd2.norm() < 1e-4);
}

TEST_CASE("the single-precision solve split over the elimination tree: the same bits on any number of threads") {
  if (!have_cholmod()) return;
  const FloatFactorSettings every_factor(0);
  // Wide enough that nested dissection leaves two big subtrees under a thin top separator.
  const SpMatC K = test::magnetic_grid(90, 1e-2);
  const Eigen::MatrixXcd b = random_rhs(K.rows(), 2);
  SparseCholesky exact;
  exact.factorize(K);
  const Eigen::MatrixXcd xd = exact.solve(b);
  SparseCholesky single;
  single.factorize(K);
  if (!single.keep_single_precision()) {
    MESSAGE("no float kernels on this CPU: nothing to split");
    return;
  }
  const std::size_t shared = single.single_precision_shared_columns();
  MESSAGE("columns shared by both halves: " << shared << " of " << K.rows());
  CHECK(shared > 0);
  CHECK(shared < static_cast<std::size_t>(K.rows()) / 4);
  single.set_threads(1);
  const Eigen::MatrixXcd x1 = single.solve(b);
  for (Index j = 0; j < b.cols(); ++j) CHECK((x1.col(j) - xd.col(j)).norm() / xd.col(j).norm() < 1e-4);
  for (int threads : {2, 4}) {
    CAPTURE(threads);
    single.set_threads(threads);
    CHECK(same_bits(single.solve(b), x1));
  }
}

TEST_CASE("the fallback keeps the double factor, and small factors stay in double by default") {
  if (!have_cholmod()) return;
  const SpMatC K = test::magnetic_grid(30, 1e-2);
  const Eigen::MatrixXcd b = random_rhs(K.rows(), 2);
  SparseCholesky exact;
  exact.factorize(K);
  const Eigen::MatrixXcd xd = exact.solve(b);
  {
    const FloatFactorSettings forced(0, FloatFactorKernels::Fallback);
    CHECK(!float_factor_kernels_available());
    SparseCholesky c;
    c.factorize(K);
    CHECK(!c.keep_single_precision());
    CHECK(!c.single_precision());
    CHECK(same_bits(c.solve(b), xd));
  }
  {
    const FloatFactorSettings by_default(kFloatFactorMinEntries);
    SparseCholesky c;
    c.factorize(K);
    CHECK(!c.keep_single_precision());  // 900 unknowns: far below 2^20 factor entries
    CHECK(same_bits(c.solve(b), xd));
  }
}

TEST_CASE("a continuation preconditioned in single precision: valid, the same bits on any thread count, and as good as in double") {
  // Every loop of the solve is cut into pieces fixed by the face and sums in a fixed order, the
  // factorisation runs on one thread whatever the count, and the float solves split the
  // elimination tree the same way for any count: the layout is bit-identical across counts.
  const TriMesh m = test::saddle(40);
  Options o = test::with_s(1.0);
  FlattenResult fallback;
  {
    const FloatFactorSettings forced(0, FloatFactorKernels::Fallback);
    fallback = test::solve(m, o);
  }
  const FloatFactorSettings every_factor(0);
  o.threads = 1;
  const FlattenResult first = test::solve(m, o);
  for (int threads : {1, 2, 3}) {
    CAPTURE(threads);
    o.threads = threads;
    const FlattenResult one = test::solve(m, o);
    REQUIRE(one.uv.size() == first.uv.size());
    CHECK(std::memcmp(one.uv.data(), first.uv.data(), sizeof(Complex) * static_cast<size_t>(one.uv.size())) == 0);
    CHECK(one.report.quality.flips == 0);
    CHECK(one.report.quality.boundary_intersections == 0);
    MESSAGE("score: float preconditioner " << one.report.quality.score << ", double " << fallback.report.quality.score
                                           << "; CG iterations " << one.report.iterative_iterations << " / "
                                           << fallback.report.iterative_iterations);
    CHECK(std::abs(one.report.quality.score - fallback.report.quality.score) < 1e-6);
    // Really preconditioned in float where the build and the CPU can: the iterates differ in their
    // last digits.
    if (have_cholmod() && float_factor_kernels_available())
      CHECK(std::memcmp(one.uv.data(), fallback.uv.data(), sizeof(Complex) * static_cast<size_t>(one.uv.size())) != 0);
  }
}
