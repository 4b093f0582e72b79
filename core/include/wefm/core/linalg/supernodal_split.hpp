#pragma once
// Two groups of disjoint subtrees of a supernodal elimination tree, and their common ancestors.
//
// Why: supernodes in different subtrees share no column, so the numeric factorisation and the
// triangular solves can work on the two groups at once; only the ancestors (with nested
// dissection, the top separators: a few percent of the factor) wait for both. The split depends on
// the factor's structure alone, never on a thread count, so results computed group by group are the
// same whether the groups run one after the other or side by side.
#include <cstdint>
#include <vector>

#include "wefm/core/linalg/float_supernodal_solve.hpp"

namespace wefm {

struct SupernodalSplit {
  std::vector<std::uint8_t> owner;  // per supernode: 1 or 2 (its group), 0 (the common ancestors)
  std::vector<int> group[2];        // each group's supernodes, increasing
  std::vector<int> rest;            // the ancestors, increasing
  bool empty() const { return owner.empty(); }
};

// Splits by work (entries of each supernode's rectangle): the heaviest subtree is replaced by its
// children while that shortens the longer group plus the ancestors, and subtrees go to the lighter
// group, heaviest first. Empty when the supernodes are not in postorder (a subtree is then not a
// range) or the split would save less than 10% of the work.
SupernodalSplit split_supernodal_tree(const SupernodalView& f);

}  // namespace wefm
