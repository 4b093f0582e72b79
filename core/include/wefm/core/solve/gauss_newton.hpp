#pragma once
// The WEFM energy at s > 0 with rho a function of the layout (METHOD §3, §5), minimised by damped
// Gauss-Newton. rho_h = L_h / |z_I2 - z_I1| makes the prediction z_I1 + alpha d + i beta L^s
// |d|^-s d, whose derivative in d has a complex-linear part (1 - s/2) and an anti-linear part s/2.
// Lagging rho (the paper's fixed point) treats all of it as complex-linear: the iteration then
// diverges on smooth faces from s ~ 0.75 (measured on a 100k-triangle bump) and at s = 2, where
// the complex-linear part vanishes. Gauss-Newton keeps both parts (a real 2n system), decreases the
// energy at every step (line search, Levenberg-Marquardt damping) and converges where the rho
// update reaches a fixed point. Its steps are solved by CG on the real system, preconditioned by
// the complex-linear part (Hermitian, the pattern of the s = 0 energy).
#include <algorithm>
#include <cmath>
#include <vector>

#include "wefm/core/method/coefficients.hpp"
#include "wefm/core/method/options.hpp"
#include "wefm/core/linalg/partitioned_kkt.hpp"
#include "wefm/core/method/seam_substitution.hpp"
#include "wefm/core/method/shape_barrier.hpp"
#include "wefm/core/linalg/sparse_cholesky.hpp"

namespace wefm {

// d/dz of a residual term: l dz + m conj(dz).
struct Entry {
  Index use;
  Complex l, m;
};

struct GaussNewtonReport {
  int iterations = 0;
  double rho_change = 0;  // max relative change of rho over the last step
  double energy = 0;
  bool converged = false;
  bool cut = false;  // ended at a step cut short, with stop_at_cut set (see set_stop_at_cut)
};

// Whether the Gauss-Newton steps' conjugate gradients deflate the layout's rotation (on by default;
// process-wide, for tests and measurements that compare with and without).
void set_rotation_deflation(bool on);
bool rotation_deflation();

class GaussNewton {
 public:
  // K_pattern: the Hermitian energy at s = 0 (its pattern is the pattern of every Gauss-Newton
  // matrix). rows: constraints over the reduced unknowns that every step must keep (caller rows,
  // cycle closures); they hold at the starting layout.
  // K_pattern is taken over (swapped out: Eigen 3.4's sparse matrices have no move constructor, and
  // a copy of K would be a second matrix of the problem's size at the peak); the caller's matrix is
  // left empty.
  // threads: as set_threads, for the constructor's own passes too (weights, block offsets).
  GaussNewton(const Topology& tp, const Coefficients& c, const SpMatC* B, double k, Residual form, SpMatC& K_pattern,
              const SeamSubstitution& sub, std::vector<LinearRow> rows, Backend backend, double min_beta, int threads = 1);

  // The gauge v = sum_k g_k y_k (a vector between two far uses). For s >= 1 only its direction is
  // held (rotation) and the size is an unknown like any other. Below s = 1 the energy tends to 0 as
  // the layout shrinks (its altitude term has degree 1 - s; measured: a torus face collapses
  // geometrically at s = 0.25) and need not have a local minimum in size, so v is held whole: the
  // layout keeps the size it starts with (the 3D area). Without a gauge, rows hold rotation and size.
  void set_gauge_row(LinearRow row) { gauge_row_ = std::move(row); }

  // Precondition with `chol`, the factor of K with uses x0, x1 split off (PartitionedKKT's K_PP),
  // refactorised in place with the Gauss-Newton values: its symbolic analysis is reused. Only
  // without substituted seams (their reduced unknowns have another pattern). x0 and x1 are
  // eliminated exactly (a 2x2 Schur complement): preconditioning them by their diagonal alone
  // took 3.5x the CG iterations at 1M triangles.
  // Returns false (and shares nothing) when seams are substituted.
  bool share_factor(SparseCholesky& chol, Index x0, Index x1);

  // Threads for the linearisation, the energy passes and the CG products (Options::threads; the
  // preconditioner's own in its factor). Every sum runs in an order fixed by the face alone.
  void set_threads(int threads) { threads_ = threads; }

  // The point sizes are changed about: one the caller's constraints keep fixed under scaling.
  void set_scale_center(Complex c) { center_ = c; }

  double energy(const VectorXc& z, double s) const;

  // With `on`, run() stops at the first step that is not a full Gauss-Newton step (the flip bound
  // or the line search cut it short) and reports `cut`: a tentative continuation step gives way to
  // shorter ones there (core/src/solve/flatten.cpp).
  void set_stop_at_cut(bool on) { stop_at_cut_ = on; }

  // What the iteration carries from one step to the next (damping, the factor's age), to start
  // again from an earlier layout as if the steps since had not been taken. The factor's values are
  // not saved: when it was refactorised since, the next step refactorises it (which also renews
  // what is cached with it); at the start of a solve it is unfactorised anyway, and the restored
  // run takes the very steps of the saved one.
  struct State {
    double lambda = 0;
    bool factored = false;
    int last_pcg = 0, fresh_pcg = 0;
    bool baseline_pending = false;
    std::int64_t refactorisations = 0;
  };
  State state() const { return {lambda_, factored_, last_pcg_, fresh_pcg_, baseline_pending_, refactorisations_}; }
  void restore(const State& st) {
    lambda_ = st.lambda;
    factored_ = st.factored && refactorisations_ == st.refactorisations;
    last_pcg_ = st.last_pcg;
    fresh_pcg_ = st.fresh_pcg;
    baseline_pending_ = st.baseline_pending;
  }

  // Scales z about its centroid by the local minimiser of E(a z); returns a (1 when none exists)
  // and writes the energy after it (E(a) = a^2 P - 2 a^(2-s) Q + a^(2-2s) R: no second pass).
  double rescale(VectorXc& z, double s, double& energy_after);

  // Iterates from z (updated in place) at s until the rho change falls below tol or max_it.
  // `check` is called once per iteration (progress, cancellation).
  // With `free_scale` each step is followed by the size that minimises the energy along z -> a z
  // (a safeguard for s >= 1, where the size is also a Gauss-Newton unknown).
  template <class Check>
  GaussNewtonReport run(VectorXc& z, double s, double tol, int max_it, bool free_scale, Check&& check) {
    GaussNewtonReport rep;
    double e_prev = 0;
    double e_window[5] = {};  // energies of the last five iterations
    for (int it = 0; it < max_it; ++it) {
      check(it);
      rep.rho_change = step(z, s, rep.energy);
      if (stop_at_cut_ && !last_full_) {
        rep.iterations = it + 1;
        rep.cut = true;
        return rep;
      }
      if (it == 0) {
        e_prev = last_e0_;  // the energy at the start, from the first linearisation
        std::fill(e_window, e_window + 5, e_prev);
      }
      if (free_scale) rep.rho_change = std::max(rep.rho_change, std::abs(rescale(z, s, rep.energy) - 1.0));
      rep.iterations = it + 1;
      // Converged when rho settles, or when the energy no longer decreases (a flat valley where
      // rho drifts without changing the fit): below 1e-9 relative, or below 1e-7 on an undamped
      // step. Measured on the sphere with a small hole at s = 1: from iteration 25 on, each step
      // lowers the energy by 1e-8 while the max rho change, held up by two near-collapsed
      // triangles, creeps down by 0.0004 a step.
      // Or a slow tail: the energy fell by less than 1e-5 of itself per iteration over the last
      // five. Measured on a Ball.brep sphere face at s = 2: the score moves from .8448 (iteration
      // 35, where this stops) to .8453 (iteration 98, the 1e-7 rule) while a few triangles near the
      // poles keep the max rho change at 2-7 %.
      const double decrease = e_prev - rep.energy;
      const bool stalled = decrease <= 1e-9 * e_prev || (decrease <= 1e-7 * e_prev && lambda_ <= 1e-6) ||
                           (it >= 5 && e_window[it % 5] - rep.energy <= 5e-5 * e_window[it % 5]);
      e_window[it % 5] = rep.energy;
      e_prev = rep.energy;
      if (rep.rho_change < tol || stalled) {
        rep.converged = true;
        break;
      }
    }
    return rep;
  }

  // Analyses and factorisations of the factor of its own (a shared factor counts in its owner).
  FactorCounters& counters() { return own_chol_.counters(); }
  SparseCholesky& own_factor() { return own_chol_; }
  std::int64_t pcg_iterations() const { return pcg_iterations_; }
  double time_assembly() const { return t_assembly_; }

 private:
  // One damped step; returns the max relative rho change it made.
  double step(VectorXc& z, double s, double& energy_out);
  Eigen::MatrixXd step_constraints(const VectorXc& z, double s, Index nr) const;
  Eigen::VectorXd step_rotation(const VectorXc& z, Index nr) const;
  // The smallest t > 0 at which z + t dz flips a triangle that is positive in z (infinity if none).
  double first_flip(const VectorXc& z, const VectorXc& dz) const;
  // The shape barrier's energy at z, and (with Kc_, S_, g) its rows added to the linearisation: a
  // pass of their own for the per-use residual; the per-half-edge passes add them triangle by
  // triangle as they go.
  double barrier_energy(const VectorXc& z) const;
  void linearise_barrier(const VectorXc& z, VectorXc& g, double& energy);
  // Projected CG on the step system; `Kc`, `S` are the (reduced) complex-linear and anti-linear
  // parts of the Gauss-Newton matrix: H dy = Kc dy + S conj(dy). `rotation`: the layout's
  // infinitesimal rotation over the step's unknowns (real form), which CG deflates; empty: none.
  bool solve_step(const SpMatC& Kc, const Complex* S, const Eigen::VectorXd& shift, const Eigen::VectorXd& g,
                  const Eigen::MatrixXd& C, const Eigen::VectorXd& rotation, Eigen::VectorXd& delta);
  class ProjectedCg;  // the CG of solve_step (gauss_newton.cpp)
  // Refactorises the preconditioner on Kc plus the shift.
  void refactor(const SpMatC& Kc, const Eigen::VectorXd& shift);
  // Kc_, S_, the gradient g (complex: J^H r, Re and Im interleaved in the real CG) and the energy
  // at z; also the UV base length of every half-edge (len_), against which a step's rho change is
  // measured.
  void linearise(const VectorXc& z, double s, VectorXc& g, double& energy);
  void linearise_per_use(const VectorXc& z, double s, VectorXc& g, double& energy);
  // The energy's parts along z -> a z: P (degree 1), Q (cross), R (altitude, degree 1 - s).
  struct ScaleSums {
    double P = 0, Q = 0, R = 0;
    double barrier = 0;  // the shape barrier's energy: scale-free, so outside P, Q, R
  };
  // Energy at z; with `rho_change`, also the max relative rho change against len_; with `sums`,
  // the parts rescale needs.
  double energy_at(const VectorXc& z, double s, double* rho_change, ScaleSums* sums) const;
  // Position of row a in column b of K's pattern.
  int slot(Index a, Index b) const;
  template <class F>
  void for_each_row(const VectorXc& z, double s, F&& f) const;
  template <class F>
  void for_each_row_split(const VectorXc& z, double s, F&& f) const;

  const Topology& tp_;
  const Coefficients& c_;
  const SpMatC* B_;
  Residual form_;
  std::vector<double> w_;   // PerUse: w per half-edge (eq. 9)
  std::vector<double> sw_;  // PerHalfEdge: sqrt(w), the weight of each half-edge's row
  const SeamSubstitution& sub_;
  ShapeBarrier barrier_;
  std::vector<std::vector<size_t>> opposite_;  // PerUse: half-edges opposite each use
  bool identity_ = true;
  // The Gauss-Newton matrix in complex form, on the pattern of K: Kc_ (Hermitian) is its
  // complex-linear part and the preconditioner, S_ (complex symmetric, values on Kc_'s pattern)
  // its anti-linear part. A real 2n x 2n copy (four doubles per entry of K, and their indices)
  // would take about twice the memory of Kc_ and more memory traffic per product.
  SpMatC Kc_;
  std::vector<Complex> S_;
  std::vector<int> btb_slot_;  // B^H B (constant: the boundary term is complex-linear) in Kc_'s pattern
  std::vector<Complex> btb_;
  std::vector<double> len_;    // UV base length per half-edge at the last linearisation
  // PerHalfEdge: per triangle, the offset of entry (a, b) of its block in column b of Kc_
  // (kFarOffset: found by search, for columns longer than a byte can index).
  std::vector<std::uint8_t> block_offset_;
  static constexpr std::uint8_t kFarOffset = 255;
  std::vector<LinearRow> rows_;
  LinearRow gauge_row_;
  Complex center_{0, 0};
  // Preconditioner: the complex factor applied to real vectors (Re, Im interleaved per unknown):
  // the real form of a Hermitian matrix is symmetric, so the complex factor preconditions the real CG.
  void precondition(const Eigen::MatrixXd& r, Eigen::MatrixXd& out);
  SparseCholesky own_chol_;
  SparseCholesky* chol_ = &own_chol_;
  // With a shared factor: use -> index in K_PP (-1 for the split uses), and Kc_ value -> K_PP value.
  std::vector<Index> p_of_;
  std::vector<Index> kc_to_pp_;
  Index split_[2] = {-1, -1};
  SpMatC Kpp_;
  struct SplitEntry {
    Index value, p, x;  // Kc_ value index, its K_PP row, its split column (0, 1)
  };
  std::vector<SplitEntry> px_entries_;
  Eigen::MatrixXcd Wx_;    // K_PP^{-1} K_PX
  Eigen::Matrix2cd Sx_;    // K_XX - K_XP K_PP^{-1} K_PX
  Eigen::MatrixXcd pre_b_, pre_x_;  // preconditioner buffers (kept: no allocation per CG iteration)
  // M^{-1} e_k for the unknowns k of the constraint rows (real form), while the factor is unchanged.
  static constexpr size_t kMaxCachedUnits = 8;
  std::vector<Index> unit_uses_;
  Eigen::MatrixXd units_;
  bool units_valid_ = false;
  double last_e0_ = 0;         // energy at the last linearisation
  ScaleSums accepted_sums_;  // at the layout the last line search accepted, until rescale uses them
  bool accepted_sums_valid_ = false;
  double lambda_ = 1e-6;
  bool last_full_ = true;  // the last step went the whole Gauss-Newton direction at the damping it started with
  bool stop_at_cut_ = false;
  bool factored_ = false;
  std::int64_t refactorisations_ = 0;
  int last_pcg_ = 0;   // iterations of the last step's conjugate gradients
  int fresh_pcg_ = 0;  // the same, for the first step solved with the current factor
  bool baseline_pending_ = false;  // refactorised mid-step: the next step sets fresh_pcg_
  // Refactorise when the last step took this many CG iterations more than the first one with the
  // current factor: a refactorisation costs a dozen or more single-vector preconditioner solves,
  // so it pays only when the factor has gone stale. A factor a few steps old often needs no more
  // iterations than a fresh one, so a rule on the iteration count alone (any step over a fixed
  // count) would refactorise where nothing is gained
  // (docs/PERFORMANCE.md, "Measurements behind design choices").
  static constexpr int kRefactorExtra = 10;
  // Inexact Newton: CG stops at 1e-2 in the preconditioned residual norm (1e-4 in r.z). At 1M
  // triangles (s = 1) 1e-4 in the norm took 40 CG iterations where 1e-2 takes 22, for the same
  // Gauss-Newton iterations and the same layout to 1e-9 in score; on the sphere with a small hole
  // the tighter target ran out of CG iterations and ended at s = 0. A forcing term tightening
  // with the gradient (Eisenstat-Walker) was tried there and needed more iterations, not fewer.
  static constexpr double kCgTolerance = 1e-4;
  static constexpr int kMaxCgIterations = 50;
  std::int64_t pcg_iterations_ = 0;
  double t_assembly_ = 0;
  int threads_ = 1;
  static constexpr Index kHalves = 2;  // the linearisation's split of the uses
  static constexpr Index kBlocks = 8;  // the energy passes' blocks of triangles
};

}  // namespace wefm
