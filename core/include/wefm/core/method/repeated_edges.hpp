#pragma once
// Constraint rows for the modes of a repeated edge (METHOD §6, plus rotational periodicity).
#include <vector>

#include "wefm/core/linalg/linear_row.hpp"
#include "wefm/core/mesh/topology.hpp"

namespace wefm {

// Rows making the edge's two sides obey `mode` (none for Free). `rotation` = e^{i theta} for
// Rotational. Rows that reduce to 0 = 0 (a seam end shared by both sides) are dropped.
std::vector<LinearRow> repeated_edge_rows(const RepeatedEdge& edge, EdgeMode mode, Complex rotation = {1, 0});

// Puts the two sides of every Scar edge (modes indexed by edge id) at the same point: the
// constraint holds them together only to rounding, and two copies of one chain a rounding apart
// cross each other, so a glued scar counted as a boundary self-intersection.
void glue_scars(const Topology& tp, const std::vector<EdgeMode>& modes, VectorXc& z);

// Whether the edge's two sides lie on each other in layout z: every pair of matching uses closer
// than 1e-6 of the side's extent. Such a layout is the scar whatever mode produced it.
bool sides_coincide(const RepeatedEdge& edge, const VectorXc& z);

// Best rotation e^{i theta} taking side b's chain onto side a's in layout z (least squares).
Complex estimate_rotation(const RepeatedEdge& edge, const VectorXc& z);

}  // namespace wefm
