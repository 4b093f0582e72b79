#include "wefm/core/linalg/ordering_choice.hpp"

#include <cmath>

namespace wefm {

namespace {

// Flops per factor entry above which AMD's order is worth comparing with the dissection's. The
// dissection gives about 310 on the 1M faces measured (disk, cylinder); AMD gave 222 on the 1M
// plate (kept, without a second analysis), 427 on a 1M cylinder cut along its seam (15.4 GFlop,
// 36.1M entries, against the dissection's 8.5 GFlop, 27.1M) and 666 on the 1M disk (poor).
constexpr double kDoubtfulFlops = 300;

// CHOLMOD's poor test is not made for large planar graphs: the flops per entry of any good order
// grow there as sqrt(n) / log(n), and the dissection's passed 500 between 1M triangles (319 on the
// disk) and 4M (561), which sent the 4M disk to METIS, whose analysis is then a large share of the
// solve, for a factorisation no cheaper. The planar bound is the flops' growth for an optimal
// order on a planar graph (Lipton-Tarjan), with room: the dissection gives 24.3 n^1.5 on the 1M
// disk and 24.6 on the 4M one; AMD's poor orders of the disk 83 and 81.
constexpr double kPlanarFlops = 50;

}  // namespace

// CHOLMOD's form of the test: at least 5 factor entries per matrix entry, each costing at least
// flops_per_entry.
static bool costly_fill(const OrderCounts& o, double anz, double flops_per_entry) {
  return o.lnz >= 5 * anz && o.fl >= flops_per_entry * o.lnz;
}

bool poor_order(const OrderCounts& o, double anz) { return costly_fill(o, anz, 500); }

bool doubtful_order(const OrderCounts& o, double anz) { return costly_fill(o, anz, kDoubtfulFlops); }

bool dissection_acceptable(const OrderCounts& nd, double anz, double n) {
  return !poor_order(nd, anz) || nd.fl <= kPlanarFlops * std::pow(n, 1.5);
}

}  // namespace wefm
