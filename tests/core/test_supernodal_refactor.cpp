// wefm's own supernodal numeric factorisation (supernodal_refactor.hpp) on CHOLMOD's analysis: the
// factor CHOLMOD would give to rounding, the same bits on any number of threads, a matrix that is
// not positive definite still refused, and the switch back to CHOLMOD's own factorisations.
#include <random>

#include <doctest/doctest.h>
#include "same_bits.hpp"

#include "magnetic_grid.hpp"
#include "wefm/core/sys/error.hpp"
#include "wefm/core/linalg/sparse_cholesky.hpp"

using namespace wefm;
using wefm::test::same_bits;

namespace {

Eigen::MatrixXcd rhs(Index n) {
  std::mt19937 rng(3);
  std::normal_distribution<double> g;
  Eigen::MatrixXcd b(n, 2);
  for (Index i = 0; i < b.size(); ++i) b.data()[i] = Complex(g(rng), g(rng));
  return b;
}

}  // namespace

TEST_CASE("the own supernodal factorisation gives CHOLMOD's factor to rounding, the same bits on any thread count") {
  if (!have_cholmod()) return;
  const SpMatC K1 = test::magnetic_grid(80, 1e-2, 5), K2 = test::magnetic_grid(80, 1e-2, 9);
  const Eigen::MatrixXcd b = rhs(K1.rows());
  // CHOLMOD's own factorisations (the switch off): the reference, and its refactorisation.
  set_supernodal_refactor(false);
  Eigen::MatrixXcd x_cholmod;
  {
    SparseCholesky fresh;
    fresh.factorize(K2);
    x_cholmod = fresh.solve(b);
    SparseCholesky again;
    again.factorize(K1);
    again.factorize(K2);
    CHECK(same_bits(again.solve(b), x_cholmod));
  }
  set_supernodal_refactor(true);
  Eigen::MatrixXcd x1;
  for (int threads : {1, 2, 3}) {
    CAPTURE(threads);
    SparseCholesky c;
    c.set_threads(threads);
    c.factorize(K1);  // analysis, then the own factorisation into CHOLMOD's layout
    const Eigen::MatrixXcd first = c.solve(b);
    CHECK((K1 * first - b).norm() / b.norm() < 1e-10);
    c.factorize(K2);  // a refactorisation
    CHECK(c.counters().analyses == 1);
    CHECK(c.counters().factorizations == 2);
    const Eigen::MatrixXcd x = c.solve(b);
    const double err = (x - x_cholmod).norm() / x_cholmod.norm();
    MESSAGE("relative difference to CHOLMOD's factorisation: " << err);
    CHECK(err < 1e-12);
    CHECK(err > 0);  // really computed apart from CHOLMOD: the sums' order differs
    CHECK((K2 * x - b).norm() / b.norm() < 1e-10);
    if (threads == 1) x1 = x;
    else CHECK(same_bits(x, x1));
  }
}

TEST_CASE("the own refactorisation refuses a matrix that is not positive definite, and the next one analyses again") {
  if (!have_cholmod()) return;
  const SpMatC K = test::magnetic_grid(40, 1e-2, 5);
  SparseCholesky c;
  c.factorize(K);
  SpMatC bad = K;
  bad.coeffRef(100, 100) = Complex(-5.0, 0.0);
  bool refused = false;
  try {
    c.factorize(bad);
  } catch (const Error& e) {
    refused = e.code() == Errc::not_positive_definite;
  }
  CHECK(refused);
  c.factorize(K);  // a fresh analysis (the failure cleared the pattern) and CHOLMOD's factorisation
  CHECK(c.counters().analyses == 2);
  const Eigen::MatrixXcd b = rhs(K.rows());
  CHECK((K * c.solve(b) - b).norm() / b.norm() < 1e-10);
}
