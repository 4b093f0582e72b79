#pragma once
// K = A^H A + B^H B for the per-half-edge residual, assembled straight into a sparsity pattern that
// is built once per topology and boundary operator: no A (nine entries per triangle), no triplets,
// no sparse product. Each triangle adds a 3x3 Hermitian block on its uses; the pattern stores, for
// every corner, where the entries of its block column land in K, so assembling is a gather per
// column. A column is summed by one thread in ascending corner order (then B^H B), so K is
// bit-identical for every thread count and exactly Hermitian.
#include <vector>

#include "wefm/core/sys/types.hpp"
#include "wefm/core/mesh/use_corners.hpp"

namespace wefm {

class EnergyAssembler {
 public:
  // B may be null or empty (no boundary term). The topology must outlive the assembler.
  EnergyAssembler(const Topology& topo, const SpMatC* B, int threads = 1);

  // K for weights w (compute_weights) and sigma (compute_sigma), both per half-edge.
  SpMatC assemble(const std::vector<double>& w, const std::vector<Complex>& sigma, int threads = 1) const;

  Index non_zeros() const { return static_cast<Index>(row_.size()); }
  // K's pattern: compressed columns, rows ascending in each column.
  const std::vector<int>& outer() const { return outer_; }
  const std::vector<int>& rows() const { return row_; }

  // Takes B's values for the boundary term, B with the pattern the assembler was built with (its
  // values then may have been anything: the pattern alone sets K's). False, and nothing changed,
  // when B^H B's pattern differs from the one built with.
  bool set_boundary(const SpMatC* B);

 private:
  const Topology* tp_;
  UseCorners uc_;
  std::vector<int> outer_, row_;  // K's pattern (CSC), rows ascending in each column
  std::vector<int> slot_;         // 3 per corner c: where the block column of c lands (row corner 3t, 3t+1, 3t+2)
  SpMatC btb_;                    // B^H B
  std::vector<int> btb_slot_;     // per non-zero of btb_: its place in K
};

}  // namespace wefm
