// The continuation's preconditioner alone: solves with the single-precision supernodal factor
// (core/src/linalg/float_supernodal_solve.cpp), the step that each CG iteration of a Gauss-Newton step
// pays. Its matrix is a magnetic Laplacian of an n x n grid with diagonals (the test matrix of the
// factorisation tests): Hermitian, complex, with supernodes of every size. n = 700 has 490k unknowns
// and 41M factor entries, about a 1M-triangle face's K_PP.
//
//   wefm-bench-precondition [N] [REPEATS]      (defaults 700, 20)
//
// Prints, for 1 and 2 threads, the best wall time of one solve (forward and backward) and the
// factor bytes it streams per second.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>

#include "magnetic_grid.hpp"
#include "wefm/core/linalg/float_supernodal_solve.hpp"
#include "wefm/core/linalg/sparse_cholesky.hpp"

int main(int argc, char** argv) {
  using namespace wefm;
  const int n = argc > 1 ? std::atoi(argv[1]) : 700, repeats = argc > 2 ? std::atoi(argv[2]) : 20;
  if (n < 2 || repeats < 1) {
    std::fprintf(stderr, "usage: wefm-bench-precondition [N >= 2] [REPEATS >= 1]\n");
    return 2;
  }
  if (!have_cholmod() || !float_factor_kernels_available()) {
    std::fprintf(stderr, "wefm-bench-precondition: needs CHOLMOD and a CPU with AVX2 + FMA\n");
    return 2;
  }
  const SpMatC K = test::magnetic_grid(n, 1e-2);
  for (int threads : {1, 2}) {
    SparseCholesky chol;
    chol.set_threads(threads);
    chol.factorize(K);
    if (!chol.keep_single_precision()) {
      std::fprintf(stderr, "wefm-bench-precondition: the factor did not convert to single precision\n");
      return 1;
    }
    const Eigen::MatrixXcd b = Eigen::MatrixXcd::Ones(K.rows(), 1);
    Eigen::MatrixXcd x = chol.solve(b);
    double best = 1e30;
    for (int r = 0; r < repeats; ++r) {
      const auto t0 = std::chrono::steady_clock::now();
      x = chol.solve(b);
      best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    const double bytes = 2.0 * 8.0 * static_cast<double>(chol.factor_entries());  // read forward and backward
    std::printf("n %d: %lld unknowns, %zu factor entries, threads %d: best solve %.2f ms (%.1f GB/s of factor), x[0] = %.9g\n", n,
                static_cast<long long>(K.rows()), chol.factor_entries(), threads, 1e3 * best, bytes / best * 1e-9, x(0).real());
  }
  return 0;
}
