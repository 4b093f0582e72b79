// The geometric nested dissection order (nested_dissection.hpp): a permutation, fill close to
// minimum degree's on a plain grid, unharmed by couplings along the boundary (the boundary
// term's, which ruin minimum degree at 1M triangles), deterministic; and SparseCholesky keeps
// CHOLMOD's minimum degree wherever that is not poor.
#include <cstring>
#include <numeric>
#include <random>
#include <vector>

#include <Eigen/SparseCholesky>
#include <doctest/doctest.h>

#include "magnetic_grid.hpp"
#include "wefm/core/linalg/nested_dissection.hpp"
#include "wefm/core/linalg/sparse_cholesky.hpp"

using namespace wefm;

namespace {

std::vector<Vec3> grid_points(int n) {
  std::vector<Vec3> p(static_cast<size_t>(n) * static_cast<size_t>(n));
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) p[static_cast<size_t>(j * n + i)] = Vec3(i, j, 0.1 * std::sin(0.3 * i));
  return p;
}

// The grid's boundary cycle, each use coupled with the ones two steps along it (as B^H B couples
// a loop's uses), with weights that keep the matrix positive definite.
SpMatC with_boundary_chords(const SpMatC& K, int n) {
  std::vector<int> ring;
  for (int i = 0; i < n - 1; ++i) ring.push_back(i);
  for (int j = 0; j < n - 1; ++j) ring.push_back(j * n + n - 1);
  for (int i = n - 1; i > 0; --i) ring.push_back((n - 1) * n + i);
  for (int j = n - 1; j > 0; --j) ring.push_back(j * n);
  std::vector<Eigen::Triplet<Complex>> t;
  for (int k = 0; k < K.outerSize(); ++k)
    for (SpMatC::InnerIterator it(K, k); it; ++it) t.emplace_back(static_cast<int>(it.row()), static_cast<int>(it.col()), it.value());
  const size_t m = ring.size();
  for (size_t k = 0; k < m; ++k) {
    const int a = ring[k], b = ring[(k + 2) % m];
    t.emplace_back(a, a, 0.5);
    t.emplace_back(b, b, 0.5);
    t.emplace_back(a, b, -0.5);
    t.emplace_back(b, a, -0.5);
  }
  SpMatC C(K.rows(), K.cols());
  C.setFromTriplets(t.begin(), t.end());
  C.makeCompressed();
  return C;
}

bool is_permutation(const std::vector<int>& perm, size_t n) {
  std::vector<char> seen(n, 0);
  if (perm.size() != n) return false;
  for (int p : perm) {
    if (p < 0 || static_cast<size_t>(p) >= n || seen[static_cast<size_t>(p)]) return false;
    seen[static_cast<size_t>(p)] = 1;
  }
  return true;
}

// Entries of the Cholesky factor of K eliminated in the order perm (perm[k]: k-th unknown).
Index fill_in_order(const SpMatC& K, const std::vector<int>& perm) {
  std::vector<int> to(perm.size());
  for (size_t k = 0; k < perm.size(); ++k) to[static_cast<size_t>(perm[k])] = static_cast<int>(k);
  std::vector<Eigen::Triplet<Complex>> t;
  for (int k = 0; k < K.outerSize(); ++k)
    for (SpMatC::InnerIterator it(K, k); it; ++it)
      t.emplace_back(to[static_cast<size_t>(it.row())], to[static_cast<size_t>(it.col())], it.value());
  SpMatC P(K.rows(), K.cols());
  P.setFromTriplets(t.begin(), t.end());
  Eigen::SimplicialLLT<SpMatC, Eigen::Lower, Eigen::NaturalOrdering<int>> llt(P);
  REQUIRE(llt.info() == Eigen::Success);
  return llt.matrixL().nestedExpression().nonZeros();
}

Index amd_fill(const SpMatC& K) {
  Eigen::SimplicialLLT<SpMatC, Eigen::Lower, Eigen::AMDOrdering<int>> llt(K);
  REQUIRE(llt.info() == Eigen::Success);
  return llt.matrixL().nestedExpression().nonZeros();
}

}  // namespace

TEST_CASE("geometric nested dissection: a permutation with minimum degree's fill on a grid, unharmed by boundary couplings") {
  const int n = 60;
  const SpMatC K = test::magnetic_grid(n, 1e-2);
  const std::vector<Vec3> at = grid_points(n);
  const std::vector<int> perm = geometric_nested_dissection(K.outerIndexPtr(), K.innerIndexPtr(), at);
  REQUIRE(is_permutation(perm, at.size()));
  std::vector<int> natural(at.size());
  std::iota(natural.begin(), natural.end(), 0);
  const Index nd = fill_in_order(K, perm), band = fill_in_order(K, natural), amd = amd_fill(K);

  const SpMatC C = with_boundary_chords(K, n);
  const std::vector<int> perm_c = geometric_nested_dissection(C.outerIndexPtr(), C.innerIndexPtr(), at);
  REQUIRE(is_permutation(perm_c, at.size()));
  const Index nd_c = fill_in_order(C, perm_c), amd_c = amd_fill(C);
  MESSAGE("factor entries, 60x60 grid: nested dissection " << nd << ", natural order " << band << ", AMD " << amd
                                                           << "; with boundary chords: nested dissection " << nd_c << ", AMD " << amd_c);
  CHECK(nd < band / 2);
  CHECK(nd <= 1.5 * static_cast<double>(amd));
  CHECK(nd_c <= 1.2 * static_cast<double>(nd));
}

TEST_CASE("geometric nested dissection is deterministic and survives coincident points") {
  const int n = 30;
  const SpMatC K = test::magnetic_grid(n, 1e-2);
  const std::vector<Vec3> at = grid_points(n);
  CHECK(geometric_nested_dissection(K.outerIndexPtr(), K.innerIndexPtr(), at) ==
        geometric_nested_dissection(K.outerIndexPtr(), K.innerIndexPtr(), at));
  const std::vector<Vec3> same(at.size(), Vec3(1, 2, 3));
  const std::vector<int> perm = geometric_nested_dissection(K.outerIndexPtr(), K.innerIndexPtr(), same);
  CHECK(is_permutation(perm, at.size()));
  CHECK(is_permutation(geometric_nested_dissection(K.outerIndexPtr(), K.innerIndexPtr(), at, 1), at.size()));
}

TEST_CASE("points for the ordering leave a factor alone where minimum degree's fill is not poor") {
  if (!have_cholmod()) return;
  const int n = 50;
  const SpMatC K = test::magnetic_grid(n, 1e-2);
  Eigen::MatrixXcd b = Eigen::MatrixXcd::Ones(K.rows(), 1);
  SparseCholesky plain, pointed;
  plain.factorize(K);
  pointed.set_ordering_points(grid_points(n));
  pointed.factorize(K);
  CHECK(pointed.factor_entries() == plain.factor_entries());
  const Eigen::MatrixXcd x0 = plain.solve(b), x1 = pointed.solve(b);
  CHECK(std::memcmp(x0.data(), x1.data(), sizeof(Complex) * static_cast<size_t>(x0.size())) == 0);
  CHECK(pointed.counters().analyses == 1);
}
