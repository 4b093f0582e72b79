#pragma once
// Repeated-edge constraints by substitution instead of multipliers (for the continuation, once
// every edge's mode is decided). Each constraint z_a = c z_b + q (periodic: c = 1, q a free
// translation; rotational: c = e^{i theta}, q free; scar: c = 1, q = 0) removes z_a from the
// unknowns, so a long seam costs nothing per solve; the multiplier form costs one solve per seam
// use each time the matrix is refactorised.
#include <vector>

#include "wefm/core/linalg/linear_row.hpp"
#include "wefm/core/mesh/topology.hpp"

namespace wefm {

struct SeamSubstitution {
  using RowMajor = Eigen::SparseMatrix<Complex, Eigen::RowMajor, int>;
  Index reduced = 0;                     // number of reduced complex unknowns (kept uses, then q's)
  Index kept = 0;                        // reduced unknowns that are uses; the rest are q's
  SpMatC P;                              // uses x reduced: z = P y
  RowMajor P_rows;                       // the same, for per-use access
  std::vector<Index> use_to_reduced;     // kept use -> its reduced index, -1 when substituted
  std::vector<LinearRow> leftover;       // constraints closing a cycle, over reduced unknowns
};

SeamSubstitution substitute_seams(const Topology& tp, const std::vector<EdgeMode>& mode, const std::vector<Complex>& rotation);

// y with P y = z for a z that satisfies the constraints (kept uses read off; q's from the first pair).
VectorXc reduce(const SeamSubstitution& sub, const VectorXc& z);

// A row over uses rewritten over the reduced unknowns.
LinearRow reduce_row(const SeamSubstitution& sub, const LinearRow& row);

}  // namespace wefm
