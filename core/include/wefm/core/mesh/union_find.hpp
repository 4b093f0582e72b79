#pragma once
#include <numeric>
#include <vector>

#include "wefm/core/sys/types.hpp"

namespace wefm {

class UnionFind {
 public:
  explicit UnionFind(Index n) : parent_(static_cast<size_t>(n)) { std::iota(parent_.begin(), parent_.end(), 0); }
  Index find(Index x) {
    while (parent_[x] != x) {
      parent_[x] = parent_[parent_[x]];
      x = parent_[x];
    }
    return x;
  }
  void unite(Index a, Index b) {
    a = find(a);
    b = find(b);
    if (a != b) parent_[a < b ? b : a] = a < b ? a : b;  // smaller root wins: deterministic numbering
  }

 private:
  std::vector<Index> parent_;
};

}  // namespace wefm
