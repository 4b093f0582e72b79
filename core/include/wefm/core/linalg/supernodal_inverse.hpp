#pragma once
// Selected entries of A^{-1} from a supernodal Cholesky factor, by forward solves restricted to the
// elimination tree.
//
// Why: PartitionedKKT needs K_PP^{-1} e_u at the uses of every repeated edge, and only at those
// uses. A dense solve per use reads the whole factor twice, so its cost grows with the seam length
// times the factor's size, and batches of dense right-hand sides take memory of that order. With
// A = P^T L L^H P, A^{-1}(a, b) = y_a^H y_b where y_a = L^{-1} P e_a is non-zero only on the path
// from a's supernode to the root of the supernodal elimination tree, so forward solves over the
// union of those paths suffice, and no backward solve is needed.
#include <cstddef>
#include <vector>

#include "wefm/core/linalg/float_supernodal_solve.hpp"
#include "wefm/core/sys/types.hpp"

namespace wefm {

// A^{-1}(rows, cols), |rows| x |cols|, for the Hermitian positive definite A whose complex LL^H
// factor (double values) f holds; indices are A's own (before the factor's permutation).
// Returns false, and leaves `out` empty, when the paths' blocks would hold more than
// `max_entries` complex numbers (a deep, chain-like tree, where the restriction saves little): the
// caller then solves densely. `threads`: blocks of right-hand sides share them out, with the same
// result for any count. CHOLMOD builds only (BLAS); false otherwise.
bool supernodal_inverse_entries(const SupernodalView& f, const std::vector<Index>& rows, const std::vector<Index>& cols,
                                std::size_t max_entries, int threads, Eigen::MatrixXcd& out);

}  // namespace wefm
