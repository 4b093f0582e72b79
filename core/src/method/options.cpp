#include "wefm/core/method/options.hpp"

#include <cmath>
#include <string>

#include "wefm/core/sys/error.hpp"

namespace wefm {

void validate_options(const Options& o) {
  auto bad = [](const std::string& what) { fail(Errc::invalid_argument, "option " + what); };
  if (!(o.s >= 0 && o.s <= 2)) bad("s = " + std::to_string(o.s) + " is outside [0, 2]");
  if (!(o.k >= 0 && o.k <= 1)) bad("k = " + std::to_string(o.k) + " is outside [0, 1]");
  if (!(o.boundary_weight >= 0 && std::isfinite(o.boundary_weight))) bad("boundary_weight must be finite and >= 0");
  // A floor on s_step: the continuation takes s / s_step steps.
  if (!(o.s_step >= 1e-3 && o.s_step <= 2)) bad("s_step must be in [0.001, 2]");
  if (!(o.rho_tolerance > 0)) bad("rho_tolerance must be > 0");
  if (o.max_rho_iterations < 1) bad("max_rho_iterations must be >= 1");
  if (!(o.rollout_tolerance > 0)) bad("rollout_tolerance must be > 0");
  if (o.max_rollout_sweeps < 1) bad("max_rollout_sweeps must be >= 1");
  if (std::isnan(o.score_threshold)) bad("score_threshold is NaN");
  if (o.threads < 0) bad("threads must be >= 0");
  if (!(o.memory_limit_mb >= 0)) bad("memory_limit_mb must be >= 0");
  if (!(o.min_beta > 0 && o.min_beta < 1)) bad("min_beta must be in (0, 1)");
  const int m = static_cast<int>(o.method);
  if (m < 0 || m > 1) bad("method " + std::to_string(m) + " is not a method (0 global, 1 roll-out)");
  const int e = static_cast<int>(o.default_edge_mode);
  if (e < 0 || e > 4) bad("default_edge_mode " + std::to_string(e) + " is not an edge mode (0 auto, 1 free, 2 periodic, 3 scar, 4 rotational)");
}

}  // namespace wefm
