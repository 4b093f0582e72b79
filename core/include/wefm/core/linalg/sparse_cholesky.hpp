#pragma once
// Cholesky factorisation of a Hermitian positive definite sparse matrix, through CHOLMOD when the
// build has it and Eigen's SimplicialLDLT otherwise. Symbolic analysis and numeric factorisation
// are separate so callers with a fixed sparsity pattern analyse once; counters prove it.
#include <cstddef>
#include <memory>
#include <vector>

#include "wefm/core/linalg/backend.hpp"
#include "wefm/core/sys/types.hpp"

namespace wefm {

struct FactorCounters {
  std::int64_t analyses = 0, factorizations = 0, solves = 0;
  double time_analysis = 0, time_factorization = 0, time_solve = 0;
};

bool have_cholmod();

// The OpenBLAS thread count every solve sets (openblas_set_num_threads, process-wide) when the host
// opted in (the C API's process policy); 0, the default, leaves the host's setting alone. The
// supernodal solves are chains of small BLAS calls whose pool threads spin-wait (sched_yield) on a
// busy machine, hence the opt-in (docs/PERFORMANCE.md). Returns false, changing nothing, for
// threads > 0 where the process has no OpenBLAS.
bool set_solve_blas_threads(int threads);
int solve_blas_threads();
// Sets OpenBLAS's pool to solve_blas_threads() when that is above 0; a no-op otherwise.
void apply_solve_blas_threads();

// Process-wide switch for tests and A/B timings: with true (the default) the numeric factorisations
// of a complex CHOLMOD factor are wefm's own (supernodal_refactor.hpp) on CHOLMOD's analysis; with
// false CHOLMOD does them.
void set_supernodal_refactor(bool on);

// Scalar is Complex: the Hermitian energy of the linear solves, and the complex-linear part of the
// Gauss-Newton matrices that preconditions the continuation.
template <class Scalar>
class SparseCholeskyT {
 public:
  using Matrix = Eigen::SparseMatrix<Scalar, Eigen::ColMajor, int>;
  using Dense = Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>;
  explicit SparseCholeskyT(Backend backend = Backend::Auto);
  ~SparseCholeskyT();
  SparseCholeskyT(const SparseCholeskyT&) = delete;
  SparseCholeskyT& operator=(const SparseCholeskyT&) = delete;

  // Analyses the pattern when it differs from the last one, then factorises numerically.
  // Throws Error(not_positive_definite) when the matrix is not positive definite.
  void factorize(const Matrix& K);
  // The symbolic analysis alone, of K's pattern (its values are not read), when it differs from
  // the last one analysed; returns whether it analysed. A factorize of a matrix with this pattern
  // then goes straight to the numeric factorisation. Throws Error(out_of_memory) as factorize does.
  bool analyze(const Matrix& K);
  Dense solve(const Dense& rhs);
  // Entries (rows, cols) of the factorised matrix's inverse, by forward solves restricted to the
  // elimination tree (supernodal_inverse.hpp): for many unit right-hand sides where only a few
  // entries of each solution are wanted. False when the factor is not CHOLMOD's double supernodal
  // one, or the restriction would hold more than max_entries numbers: the caller then solves.
  // Counts one solve per column of the result.
  bool inverse_entries(const std::vector<Index>& rows, const std::vector<Index>& cols, std::size_t max_entries, Dense& out);
  // Frees the factor (counters stay); the next factorize analyses again.
  void release();
  // For a factor that only preconditions from now on: after factorize (and any solve that needs
  // the double factor), converts the factor to single precision in place
  // (float_supernodal_solve.hpp); the following solve() calls use it, until the next factorize
  // brings the double factor back. Only CHOLMOD's supernodal factors with at least
  // float_factor_min_entries() entries qualify, where the CPU has the float kernels; returns
  // whether the float factor is in use (false: the double factor stays as it was).
  bool keep_single_precision();
  bool single_precision() const;
  // Columns of the single-precision factor that wait for both halves of its split solve (its
  // elimination tree's common ancestors); 0 when there is no float factor or its solve is serial.
  std::size_t single_precision_shared_columns() const;
  // Options::threads: the threads of the single-precision solves (float_supernodal_solve.hpp).
  // CHOLMOD's own OpenMP loops always run on the calling thread alone: its supernodal
  // factorisation opens a region of 4 threads (a compile-time constant of the library) per large
  // supernode, and on a machine with fewer cores than that their wake-ups spin for CPU time the
  // solve needs (docs/PERFORMANCE.md, "Measurements behind design choices"), and their sums' order
  // would depend on the thread count.
  void set_threads(int threads) { threads_ = threads; }
  // Options::memory_limit_mb: after each symbolic analysis, a factor whose values together with
  // `other_mb` (the rest of the solve, estimated by the caller) would exceed limit_mb is refused
  // with Error(out_of_memory) before anything is allocated for it. limit_mb 0: no limit.
  void set_memory_limit(double limit_mb, double other_mb) {
    limit_mb_ = limit_mb;
    other_mb_ = other_mb;
  }
  // A point per unknown of the next matrix analysed (then dropped). When minimum degree's fill is
  // poor by CHOLMOD's own test, a geometric nested dissection on them (nested_dissection.hpp) is
  // tried before METIS, and kept unless it is poor too. CHOLMOD builds only; empty: CHOLMOD's
  // default (AMD, then METIS when poor).
  void set_ordering_points(std::vector<Vec3> xyz) { points_ = std::move(xyz); }
  // Entries of the factor found by the last analysis (CHOLMOD's L->xsize; Eigen: L and D).
  std::size_t factor_entries() const;
  Index size() const { return n_; }
  FactorCounters& counters() { return counters_; }

 private:
  struct Impl;
  // The map of K's entries into the own numeric factorisation's layout (supernodal_refactor.hpp),
  // when it applies and is not made yet.
  void prepare_own_refactor(const Matrix& K);
  std::unique_ptr<Impl> impl_;
  FactorCounters counters_;
  Index n_ = 0;
  int threads_ = 1;
  double limit_mb_ = 0, other_mb_ = 0;
  std::vector<int> pattern_outer_, pattern_inner_;
  std::vector<Vec3> points_;
};

using SparseCholesky = SparseCholeskyT<Complex>;

}  // namespace wefm
