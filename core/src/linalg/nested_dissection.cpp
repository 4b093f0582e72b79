#include "wefm/core/linalg/nested_dissection.hpp"

#include <algorithm>
#include <utility>

namespace wefm {

std::vector<int> geometric_nested_dissection(const int* outer, const int* inner, const std::vector<Vec3>& xyz, int leaf) {
  const int n = static_cast<int>(xyz.size());
  leaf = std::max(leaf, 1);
  std::vector<int> ids(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) ids[static_cast<size_t>(i)] = i;
  std::vector<int> perm(static_cast<size_t>(n));
  int back = n;  // filled from the back: a part's separator goes after everything split from it
  std::vector<int> stamp(static_cast<size_t>(n), -1);
  std::vector<char> upper(static_cast<size_t>(n), 0);
  int round = 0;
  std::vector<int> a, b, s;
  // Ranges of ids still to split; the range pushed last is placed last among the unplaced.
  std::vector<std::pair<int, int>> todo{{0, n}};
  while (!todo.empty()) {
    const auto [lo, hi] = todo.back();
    todo.pop_back();
    const int m = hi - lo;
    if (m <= leaf) {
      for (int i = hi - 1; i >= lo; --i) perm[static_cast<size_t>(--back)] = ids[static_cast<size_t>(i)];
      continue;
    }
    Vec3 mn = xyz[static_cast<size_t>(ids[static_cast<size_t>(lo)])], mx = mn;
    for (int i = lo + 1; i < hi; ++i) {
      mn = mn.cwiseMin(xyz[static_cast<size_t>(ids[static_cast<size_t>(i)])]);
      mx = mx.cwiseMax(xyz[static_cast<size_t>(ids[static_cast<size_t>(i)])]);
    }
    int axis = 0;
    (mx - mn).maxCoeff(&axis);
    const int mid = lo + m / 2;
    std::nth_element(ids.begin() + lo, ids.begin() + mid, ids.begin() + hi, [&](int p, int q) {
      const double xp = xyz[static_cast<size_t>(p)][axis], xq = xyz[static_cast<size_t>(q)][axis];
      return xp < xq || (xp == xq && p < q);
    });
    ++round;
    for (int i = lo; i < hi; ++i) {
      const int u = ids[static_cast<size_t>(i)];
      stamp[static_cast<size_t>(u)] = round;
      upper[static_cast<size_t>(u)] = i >= mid;
    }
    a.clear();
    b.clear();
    s.clear();
    for (int i = lo; i < hi; ++i) {
      const int u = ids[static_cast<size_t>(i)];
      if (!upper[static_cast<size_t>(u)]) {
        a.push_back(u);
        continue;
      }
      bool touches = false;
      for (int p = outer[u]; p < outer[u + 1] && !touches; ++p) {
        const int w = inner[p];
        touches = w != u && stamp[static_cast<size_t>(w)] == round && !upper[static_cast<size_t>(w)];
      }
      (touches ? s : b).push_back(u);
    }
    for (auto it = s.rbegin(); it != s.rend(); ++it) perm[static_cast<size_t>(--back)] = *it;
    int k = lo;
    for (int u : a) ids[static_cast<size_t>(k++)] = u;
    const int split = k;
    for (int u : b) ids[static_cast<size_t>(k++)] = u;
    // The lower half is placed first, so it is split last (filled from the back).
    todo.emplace_back(lo, split);
    todo.emplace_back(split, k);
  }
  return perm;
}

}  // namespace wefm
