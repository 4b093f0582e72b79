#pragma once
// The caller's linear constraints (pins included) as the solver takes them: in normalised units
// (positions divided by the mean edge length) and each row scaled to a largest coefficient of 1.
#include <vector>

#include "wefm/core/linalg/linear_row.hpp"

namespace wefm {

// How far from the origin, in mean edge lengths, a constraint may place the layout. Beyond it,
// double rounding of a position (1.1e-16 of its size) exceeds 1e-6 of an edge and the layout's
// small triangles are lost; far enough beyond it, the layout overflows to infinity.
constexpr double kMaxConstraintReach = 1e10;

// Scaling a row leaves the constraint set unchanged; it keeps rows with tiny coefficients (1e-300)
// from vanishing in the KKT system. Throws invalid_constraint for a row whose right-hand side over
// its largest coefficient exceeds kMaxConstraintReach edge lengths, and for a row whose
// coefficients are all zero but whose right-hand side is not (a contradiction, 0 = c).
std::vector<LinearRow> normalised_caller_rows(const std::vector<LinearRow>& rows, double length_scale);

}  // namespace wefm
