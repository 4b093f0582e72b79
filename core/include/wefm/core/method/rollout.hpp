#pragma once
// The iterative roll-out (METHOD §4, paper §4.1): place uses one at a time from a first boundary
// edge, each at the 1/beta-weighted average of its predictions, then Gauss-Seidel sweeps. Kept as a
// method to compare against and as an initial guess; it supports pins, not general constraints.
#include <functional>

#include "wefm/core/method/coefficients.hpp"
#include "wefm/core/method/options.hpp"
#include "wefm/core/linalg/linear_row.hpp"

namespace wefm {

struct RolloutResult {
  VectorXc z;  // normalised units
  int sweeps = 0;
  bool converged = false;
  double last_move = 0;
};

// `pins`: single-term rows (use, rhs/coef); other rows throw Error(unsupported).
RolloutResult rollout(const TriMesh& mesh, const Topology& topo, const Coefficients& c, const std::vector<LinearRow>& pins,
                      const Options& options, const std::function<void(double)>& check);

}  // namespace wefm
