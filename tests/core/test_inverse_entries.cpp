// Selected entries of K^{-1} from forward solves restricted to the elimination tree
// (supernodal_inverse.hpp, SparseCholesky::inverse_entries): equal to the entries of dense solves,
// the same bits for any thread count, and refused (for the caller's dense solves) when the paths'
// blocks would exceed the budget.
#include <algorithm>
#include <cstring>
#include <random>
#include <vector>

#include <doctest/doctest.h>

#include "magnetic_grid.hpp"
#include "wefm/core/linalg/sparse_cholesky.hpp"

using namespace wefm;

namespace {

// A "seam": a row of the grid, as a repeated edge's uses lie along a curve, plus scattered
// indices; unsorted, with a repeat.
std::vector<Index> seam_and_scatter(int n, unsigned seed) {
  std::vector<Index> v;
  for (int i = 0; i < n; ++i) v.push_back(static_cast<Index>((n / 2) * n + i));
  std::mt19937 rng(seed);
  std::uniform_int_distribution<Index> any(0, n * n - 1);
  for (int k = 0; k < 12; ++k) v.push_back(any(rng));
  std::shuffle(v.begin(), v.end(), rng);
  v.push_back(v.front());
  return v;
}

}  // namespace

TEST_CASE("selected inverse entries equal those of dense solves, for any thread count") {
  if (!have_cholmod()) return;
  const int n = 48;
  const SpMatC K = test::magnetic_grid(n, 1e-2);
  const std::vector<Index> rows = seam_and_scatter(n, 3);
  std::vector<Index> cols(rows.begin(), rows.begin() + 40);
  cols.push_back(5);  // a column that is not among the rows

  SparseCholesky chol;
  chol.factorize(K);
  Eigen::MatrixXcd E = Eigen::MatrixXcd::Zero(n * n, static_cast<Index>(cols.size()));
  for (size_t c = 0; c < cols.size(); ++c) E(cols[c], static_cast<Index>(c)) = 1.0;
  const Eigen::MatrixXcd X = chol.solve(E);
  const auto solves = chol.counters().solves;

  Eigen::MatrixXcd G1, G2;
  REQUIRE(chol.inverse_entries(rows, cols, std::size_t(1) << 30, G1));
  CHECK(chol.counters().solves == solves + static_cast<std::int64_t>(cols.size()));
  REQUIRE(G1.rows() == static_cast<Index>(rows.size()));
  REQUIRE(G1.cols() == static_cast<Index>(cols.size()));
  double err = 0, big = 0;
  for (size_t c = 0; c < cols.size(); ++c)
    for (size_t r = 0; r < rows.size(); ++r) {
      err = std::max(err, std::abs(G1(static_cast<Index>(r), static_cast<Index>(c)) - X(rows[r], static_cast<Index>(c))));
      big = std::max(big, std::abs(X(rows[r], static_cast<Index>(c))));
    }
  CHECK(big > 0.1);  // K^{-1} is dense: the entries compared are not trivially zero
  CHECK(err <= 1e-10 * big);

  chol.set_threads(2);
  REQUIRE(chol.inverse_entries(rows, cols, std::size_t(1) << 30, G2));
  CHECK(G1.rows() == G2.rows());
  CHECK(std::memcmp(G1.data(), G2.data(), sizeof(Complex) * static_cast<size_t>(G1.size())) == 0);
}

TEST_CASE("selected inverse entries are refused beyond the budget, and the factor still solves") {
  if (!have_cholmod()) return;
  const int n = 30;
  const SpMatC K = test::magnetic_grid(n, 1e-2);
  const std::vector<Index> rows = seam_and_scatter(n, 5);
  SparseCholesky chol;
  chol.factorize(K);
  Eigen::MatrixXcd G;
  // The rows' own m x m block alone exceeds this.
  CHECK_FALSE(chol.inverse_entries(rows, rows, 100, G));
  CHECK(G.size() == 0);
  // A budget the m x m block fits but the paths' blocks do not.
  const std::size_t m = 42;  // distinct indices of seam_and_scatter(30, .) at most
  CHECK_FALSE(chol.inverse_entries(rows, rows, m * m + 10, G));
  Eigen::MatrixXcd e = Eigen::MatrixXcd::Zero(n * n, 1);
  e(rows[0], 0) = 1.0;
  const Eigen::MatrixXcd x = chol.solve(e);
  CHECK((K * x - e).norm() < 1e-8);
  REQUIRE(chol.inverse_entries(rows, rows, std::size_t(1) << 30, G));
  CHECK(std::abs(G(0, 0) - x(rows[0], 0)) <= 1e-10 * std::abs(x(rows[0], 0)));
}
