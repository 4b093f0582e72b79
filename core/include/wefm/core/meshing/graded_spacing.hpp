#pragma once
// Node spacing along a boundary piece that shrinks towards its ends: size(s) = min(h, s0 + g s,
// s1 + g (L - s)) for a piece of length L whose ends want segments s0 and s1, nodes at equal
// steps of the integral of 1 / size (closed form on each linear piece). With s0, s1 >= h it is
// the uniform spacing L / round(L / h). The spacing itself is common/linear_size, which the tool's
// model edges (apps/cad/cad_edge_nodes.cpp) use too.
#include <vector>

#include "wefm/core/sys/types.hpp"

namespace wefm::meshing {

// Arc lengths of the nodes from the piece's start: 0 first, the end (L) excluded; at least
// `min_count` segments.
std::vector<double> graded_spacing(double length, double h, double s0, double s1, double gradation, Index min_count);

}  // namespace wefm::meshing
