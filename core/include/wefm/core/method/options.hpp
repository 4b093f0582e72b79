#pragma once
// Solver options; defaults equal the C API's wefm_options_init.
#include "wefm/core/linalg/backend.hpp"
#include "wefm/core/mesh/topology.hpp"

namespace wefm {

enum class Method { Global = 0, Rollout = 1 };

// How the surface term sums prediction errors (METHOD §5). PerUse is eq. 7 as printed: one residual
// per use, the weighted sum of its predictions' errors; errors of opposite sign cancel inside the
// sum, so the system is barely overdetermined and near-singular along free boundaries (flips on a
// gently curved grid at s = 0 without the boundary term, measured). PerHalfEdge squares each
// prediction's error (weight w_h): every triangle's shape is fitted, and the matrix has the
// one-ring pattern of a Laplacian instead of the two-ring pattern of A^H A per use.
enum class Residual { PerHalfEdge = 0, PerUse = 1 };

struct Options {
  double s = 1.0;
  double k = 0.5;  // measured on the real sample: no flips on needle-rich faces, scores >= k = 1 everywhere
  double boundary_weight = 1.0;
  bool curvature_adjust = true;
  Method method = Method::Global;
  Backend backend = Backend::Auto;
  EdgeMode default_edge_mode = EdgeMode::Auto;
  // Largest continuation step. A step up by more than 1 is tentative: where Gauss-Newton cuts one of
  // its steps short it is taken again in steps of 1 (docs/SOLVER.md, "Steps"). Measured: steps of 1
  // give the layouts of steps of 0.25 on the real sample in fewer factorisations; the tentative
  // jump to s = 2 those of steps of 1, in fewer iterations on smooth faces.
  double s_step = 2.0;
  double rho_tolerance = 1e-3;  // the last continuation step's; steps below the target s end at 10x it
  int max_rho_iterations = 50;  // Gauss-Newton iterations per step; a sphere with a small hole needs 30 at s = 1
  double rollout_tolerance = 1e-10;
  int max_rollout_sweeps = 10000;
  double score_threshold = 2.0;
  bool auto_cut = false;
  int threads = 0;
  double memory_limit_mb = 0;
  double min_beta = 1e-3;
  Residual residual = Residual::PerHalfEdge;
};

// Throws Error(invalid_argument) naming the first option out of range.
void validate_options(const Options& o);

}  // namespace wefm
