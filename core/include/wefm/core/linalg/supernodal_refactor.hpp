#pragma once
// Numeric LL^H factorisation into a CHOLMOD supernodal factor's layout, on CHOLMOD's symbolic
// analysis (its ordering, supernodes and value layout), for every factorisation of that analysis.
//
// Why: CHOLMOD's supernodal numeric factorisation opens three or four OpenMP regions per supernode,
// and libgomp ends every region, even one run by a single thread, with a futex system call: a large
// factor makes hundreds of thousands of them, a large share of the factorisation on a virtual
// machine (docs/PERFORMANCE.md, "Measurements behind design choices"). This left-looking supernodal
// factorisation (CHOLMOD's algorithm and BLAS/LAPACK kernels: ZHERK and ZGEMM for the updates,
// ZPOTRF and ZTRSM per supernode) runs without OpenMP and works on two groups of disjoint subtrees
// at once (supernodal_split.hpp). Every update is applied in an order fixed by the factor's
// structure, so the result does not depend on the number of threads. CHOLMOD still analyses,
// solves, and factorises when this is switched off (set_supernodal_refactor).
#include <cstdint>
#include <vector>

#include "wefm/core/linalg/float_supernodal_solve.hpp"
#include "wefm/core/linalg/supernodal_split.hpp"
#include "wefm/core/sys/types.hpp"

namespace wefm {

class SupernodalRefactor {
 public:
  // Maps the lower triangle of A (entries row >= column, the part CHOLMOD reads) onto the factor's
  // supernodes. f.x: the factor's values, allocated (complex, interleaved). False when an entry
  // falls outside the factor's pattern (then factorize must not be used).
  bool prepare(const SupernodalView& f, const SpMatC& A);
  bool ready() const { return ready_; }
  // The elimination tree's split of the prepared factor (empty when serial): the float factor of
  // the same analysis solves on it too.
  const SupernodalSplit& split() const { return split_; }
  void clear();
  // L L^H = P A P^T into f.x (A with the pattern given to prepare). Returns false when A is not
  // positive definite (f.x then holds garbage: the caller fails the factorisation).
  bool factorize(const SpMatC& A, int threads);

 private:
  SupernodalView f_;
  bool ready_ = false;
  SupernodalSplit split_;
  std::vector<int> col_sn_;                 // column -> supernode
  // A's lower entries grouped by supernode: value index in A, position in x (complex entries),
  // and whether the conjugate goes there (an entry above the diagonal once permuted).
  std::vector<std::int64_t> a_start_;       // per supernode, into a_value_/a_pos_
  std::vector<int> a_value_;
  std::vector<std::int64_t> a_pos_;
  std::vector<std::uint8_t> a_conj_;
};

}  // namespace wefm
