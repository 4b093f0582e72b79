#pragma once
// Solver options; defaults equal the C API's wefm_options_init.
#include "wefm/core/sparse_cholesky.hpp"
#include "wefm/core/topology.hpp"

namespace wefm {

enum class Method { Global = 0, Rollout = 1 };

struct Options {
  double s = 1.0;
  double k = 1.0;
  double boundary_weight = 1.0;
  bool curvature_adjust = true;
  Method method = Method::Global;
  Backend backend = Backend::Auto;
  EdgeMode default_edge_mode = EdgeMode::Auto;
  double s_step = 0.25;
  double rho_tolerance = 1e-3;
  int max_rho_iterations = 20;
  double rollout_tolerance = 1e-10;
  int max_rollout_sweeps = 10000;
  double score_threshold = 2.0;
  bool auto_cut = false;
  int threads = 0;
  double memory_limit_mb = 0;
  double min_beta = 1e-3;
};

// Throws Error(invalid_argument) naming the first option out of range.
void validate_options(const Options& o);

}  // namespace wefm
