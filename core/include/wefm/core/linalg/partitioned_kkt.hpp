#pragma once
// Constrained minimisation of z^H K z (METHOD §5, §7 "matrix partitioning").
//
// K is singular (translation, and similarity on developable faces), so two uses x0, x1 are split
// off and the remaining point block K_PP, positive definite, is factorised once. Every constraint
// set (gauges, caller constraints, repeated-edge candidates) is then solved through a small dense
// system in (z_x0, z_x1, multipliers): the Schur complement against K_PP. Testing a constraint set
// costs a few cached solves and one final solve, never a refactorisation.
#include <unordered_map>
#include <vector>

#include "wefm/core/linalg/linear_row.hpp"
#include "wefm/core/linalg/sparse_cholesky.hpp"

namespace wefm {

class PartitionedKKT {
 public:
  explicit PartitionedKKT(Backend backend) : chol_(backend) {}

  // Numeric factorisation of K_PP (the symbolic analysis is reused while the pattern is unchanged).
  // `points`: a 3D point per unknown of K, for the ordering should K_PP be analysed
  // (SparseCholesky::set_ordering_points, passed on in K_PP's numbering).
  void set_matrix(const SpMatC& K, Index x0, Index x1, const std::vector<Vec3>* points = nullptr);
  // The symbolic analysis of K_PP alone, ahead of K's values, in two calls: set_pattern copies K's
  // pattern (n x n, compressed columns `outer`, `inner`, rows sorted; not read afterwards) with
  // x0, x1 split off, and analyse_pattern analyses it. A set_matrix of a K with this pattern and
  // the same x0, x1 then factorises without analysing again. Both may run on a thread of their own
  // while nothing else uses this object.
  void set_pattern(Index n, const int* outer, const int* inner, Index x0, Index x1, const std::vector<Vec3>* points = nullptr);
  void analyse_pattern();

  // min z^H K z  s.t.  rows, and sum_i eta_i z_i = 0 when eta is given. Prefer fixing translation
  // with a pin and shifting afterwards: the dense eta row makes the reduced system ill-conditioned
  // (eta^T K_PP^{-1} eta is huge), which costs accuracy.
  // Throws Error(singular) when the constraints contradict each other.
  // `refine` = false skips iterative refinement (two solves a round) for a layout that only guides
  // a choice, such as the first gauge's, which only locates two far-apart boundary uses.
  VectorXc solve(const std::vector<LinearRow>& rows, const Eigen::VectorXd* eta, bool refine = true);

  // An unrefined solve that keeps what refine() needs to go on from it later, so that a layout
  // first solved only to rank it (a repeated edge's mode candidate) is refined without repeating
  // its solve. The rows and eta must be the same in both calls.
  struct Unrefined {
    VectorXc z;
    Eigen::VectorXcd lambda;  // the multipliers of the rows (and of eta, last)
  };
  Unrefined solve_unrefined(const std::vector<LinearRow>& rows, const Eigen::VectorXd* eta);
  // solve(rows, eta) from an unrefined solution: the same rounds of refinement.
  VectorXc refine(const std::vector<LinearRow>& rows, const Eigen::VectorXd* eta, Unrefined start);

  // Precompute the columns for every use in `uses` (so later solves touching them are cheap).
  void prepare(const std::vector<Index>& uses, const Eigen::VectorXd* eta);

  FactorCounters& counters() { return chol_.counters(); }
  // Frees the factorisation and the caches (before the continuation builds its own).
  void release() {
    chol_.release();
    release_caches();
  }
  // Frees everything but the factor, which the continuation refactorises in place (same pattern,
  // no second symbolic analysis, no second factor in memory).
  void release_caches() {
    unit_.clear();
    cache_valid_ = false;
    // Swapped with empty matrices: Eigen 3.4's sparse assignment keeps the old storage.
    SpMatC().swap(Kpp_);
    Eigen::SparseMatrix<Complex>().swap(K_PX_);
  }
  SparseCholesky& factor() { return chol_; }
  Index split_use(int j) const { return x_[j]; }

 private:
  struct Column {
    Eigen::VectorXcd probe;  // K_PP^{-1} source, restricted to the probe uses
    Complex eta_dot{0, 0};   // eta_P . (K_PP^{-1} source)
  };
  void build_cache(const std::vector<Index>& universe, const Eigen::VectorXd* eta);
  // x0, x1 split off K (n x n, its pattern and values; values null: the pattern of K_PP only,
  // with zero values, and K_PX, K_XX left out).
  void split(Index n, const int* outer, const int* inner, const Complex* val, Index x0, Index x1);
  // The ordering points of the next analysis, in K_PP's numbering (none when points is null).
  void set_points(const std::vector<Vec3>* points);
  // One elimination: K z + C^H lambda = f, C z = d. Returns z and writes lambda.
  VectorXc eliminate(const std::vector<LinearRow>& rows, const Eigen::VectorXd* eta, const VectorXc& f, const Eigen::VectorXcd& d,
                     Eigen::VectorXcd& lambda, bool check);
  void probed_columns(const std::vector<LinearRow>& rows, const Eigen::VectorXd* eta, Eigen::MatrixXcd& Wq, Eigen::VectorXcd& Weta,
                      Eigen::MatrixXcd& CX) const;
  void reduced_system(const std::vector<LinearRow>& rows, const Eigen::VectorXd* eta, const VectorXc& f, const Eigen::VectorXcd& d,
                      bool has_f, const Eigen::VectorXcd& g, Eigen::MatrixXcd& M, Eigen::VectorXcd& rhs) const;
  // Makes the cached columns cover every use the rows name (and eta).
  void cover(const std::vector<LinearRow>& rows, const Eigen::VectorXd* eta);
  // Up to three rounds of refinement on the full KKT residual.
  void refine_in_place(const std::vector<LinearRow>& rows, const Eigen::VectorXd* eta, VectorXc& z, Eigen::VectorXcd& lambda);
  Index p_index(Index use) const { return p_of_[static_cast<size_t>(use)]; }
  VectorXc apply_k(const VectorXc& z) const;

  SparseCholesky chol_;
  Index n_ = 0, x_[2] = {-1, -1};
  std::vector<Index> p_of_;     // use -> index in P, or -1 for x0/x1
  Eigen::SparseMatrix<Complex> K_PX_;  // |P| x 2
  Eigen::Matrix2cd K_XX_;
  // K's blocks: K_PP (factorised, and with K_PX, K_XX the residuals of iterative refinement).
  SpMatC Kpp_;
  double kscale_ = 0;  // max |K_ii|: the size residuals are judged against
  // cache
  bool cache_valid_ = false;
  const Eigen::VectorXd* cache_eta_ = nullptr;
  std::vector<Index> universe_;  // uses (not x) with cached unit columns
  std::vector<Index> probe_;     // P indices where columns are sampled: universe + neighbours of x
  std::unordered_map<Index, Index> probe_pos_;  // P index -> position in probe_
  std::unordered_map<Index, Column> unit_;      // use -> column of e_use
  Column col_x_[2], col_eta_;
};

}  // namespace wefm
