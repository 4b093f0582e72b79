#pragma once
// One sparse linear equation over complex unknowns: sum_j coef_j z_{index_j} = rhs. The method
// states its constraints in this form (pins, gauges, a caller's rows, seam closures) and the
// constrained solve (partitioned_kkt.hpp) takes them as they are; a header of its own, so that the
// code which only builds rows does not depend on the factorisation.
#include <utility>
#include <vector>

#include "wefm/core/sys/types.hpp"

namespace wefm {

struct LinearRow {
  std::vector<std::pair<Index, Complex>> terms;
  Complex rhs{0.0, 0.0};
};

}  // namespace wefm
