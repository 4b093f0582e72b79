#pragma once
// Test matrices for the sparse factorisations.
#include <random>
#include <vector>

#include "wefm/core/sys/types.hpp"

namespace wefm::test {

// A magnetic Laplacian of an n x n grid with diagonal neighbours (complex edge weights
// w e^{i theta}) plus a small shift: Hermitian positive definite, with complex off-diagonal
// entries, and with supernodes of many sizes (short columns at the leaves, wide separators at the
// top), so the kernels' full vectors and tails are all exercised. `seed` draws the weights: the
// same pattern with other values.
inline SpMatC magnetic_grid(int n, double shift, unsigned seed = 7) {
  std::vector<Eigen::Triplet<Complex>> t;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> weight(0.5, 2.0), angle(-kPi, kPi);
  auto id = [n](int i, int j) { return j * n + i; };
  auto edge = [&](int a, int b) {
    const double w = weight(rng);
    const Complex e = w * std::polar(1.0, angle(rng));
    t.emplace_back(a, a, w);
    t.emplace_back(b, b, w);
    t.emplace_back(a, b, -e);
    t.emplace_back(b, a, -std::conj(e));
  };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      if (i + 1 < n) edge(id(i, j), id(i + 1, j));
      if (j + 1 < n) edge(id(i, j), id(i, j + 1));
      if (i + 1 < n && j + 1 < n) edge(id(i, j), id(i + 1, j + 1));
      t.emplace_back(id(i, j), id(i, j), shift);
    }
  SpMatC K(n * n, n * n);
  K.setFromTriplets(t.begin(), t.end());
  K.makeCompressed();
  return K;
}

}  // namespace wefm::test
