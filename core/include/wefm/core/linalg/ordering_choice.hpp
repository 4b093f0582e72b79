#pragma once
// The rule between two fill-reducing orders of K (sparse_cholesky.cpp): AMD's, CHOLMOD's first
// choice, and the geometric nested dissection (nested_dissection.hpp), judged by CHOLMOD's counts
// of the factor each gives (Common lnz and fl: entries and flops of a simplicial LL^H).
namespace wefm {

struct OrderCounts {
  double lnz = 0;  // factor entries
  double fl = 0;   // flops
};

// CHOLMOD's test after which its default strategy tries METIS: many entries, each costing many
// flops. anz: entries of K's lower triangle, diagonal included.
bool poor_order(const OrderCounts& o, double anz);

// AMD's order is worth comparing with the dissection's (kept without a second look below this).
bool doubtful_order(const OrderCounts& o, double anz);

// The dissection's order may be used for an n-column K: not poor, or within a planar graph's
// growth of flops (n^1.5, with room), which CHOLMOD's test does not allow for at millions of
// columns. Whether it beats a usable AMD order is a comparison of flops on top of this.
bool dissection_acceptable(const OrderCounts& nd, double anz, double n);

}  // namespace wefm
