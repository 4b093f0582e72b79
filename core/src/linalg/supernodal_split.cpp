#include "wefm/core/linalg/supernodal_split.hpp"

#include <algorithm>

namespace wefm {

SupernodalSplit split_supernodal_tree(const SupernodalView& f) {
  SupernodalSplit out;
  const int ns = f.nsuper, n = f.n;
  std::vector<int> col_sn(static_cast<size_t>(n));
  std::vector<int> parent(static_cast<size_t>(ns), -1), first(static_cast<size_t>(ns)), count(static_cast<size_t>(ns), 1);
  std::vector<double> work(static_cast<size_t>(ns));
  for (int sn = 0; sn < ns; ++sn)
    for (int c = f.super[sn]; c < f.super[sn + 1]; ++c) col_sn[static_cast<size_t>(c)] = sn;
  for (int sn = 0; sn < ns; ++sn) {
    const int nc = f.super[sn + 1] - f.super[sn], nr = f.pi[sn + 1] - f.pi[sn];
    work[static_cast<size_t>(sn)] = static_cast<double>(nr) * nc + nr;
    first[static_cast<size_t>(sn)] = sn;
    if (nr > nc) {
      const int* rows = f.s + f.pi[sn];
      const int r = *std::min_element(rows + nc, rows + nr);
      if (r < 0 || r >= n) return out;
      parent[static_cast<size_t>(sn)] = col_sn[static_cast<size_t>(r)];
      if (parent[static_cast<size_t>(sn)] <= sn) return out;  // not postordered: keep the serial solve
    }
  }
  std::vector<double> subtree(work);
  std::vector<std::vector<int>> children(static_cast<size_t>(ns));
  std::vector<int> roots;
  for (int sn = 0; sn < ns; ++sn) {
    const int p = parent[static_cast<size_t>(sn)];
    if (count[static_cast<size_t>(sn)] != sn - first[static_cast<size_t>(sn)] + 1) return out;  // a subtree must be a range
    if (p < 0) {
      roots.push_back(sn);
      continue;
    }
    subtree[static_cast<size_t>(p)] += subtree[static_cast<size_t>(sn)];
    count[static_cast<size_t>(p)] += count[static_cast<size_t>(sn)];
    first[static_cast<size_t>(p)] = std::min(first[static_cast<size_t>(p)], first[static_cast<size_t>(sn)]);
    children[static_cast<size_t>(p)].push_back(sn);
  }
  double total = 0;
  for (int r : roots) total += subtree[static_cast<size_t>(r)];
  // Split the heaviest subtree into its children while that shortens the longest path (the larger
  // part plus the rest); the subtrees go to the lighter part, heaviest first.
  std::vector<int> cand = roots, best_cand;
  std::vector<int> best_bin;
  double best_cost = 0.9 * total;  // below 10% saved, stay serial
  for (int round = 0; round < 64 && !cand.empty(); ++round) {
    std::sort(cand.begin(), cand.end(), [&](int a, int b) {
      return subtree[static_cast<size_t>(a)] != subtree[static_cast<size_t>(b)] ? subtree[static_cast<size_t>(a)] > subtree[static_cast<size_t>(b)] : a < b;
    });
    double bins[2] = {0, 0}, in_parts = 0;
    std::vector<int> bin(cand.size());
    for (size_t i = 0; i < cand.size(); ++i) {
      const int b = bins[1] < bins[0] ? 1 : 0;
      bin[i] = b;
      bins[b] += subtree[static_cast<size_t>(cand[i])];
      in_parts += subtree[static_cast<size_t>(cand[i])];
    }
    const double cost = std::max(bins[0], bins[1]) + (total - in_parts);
    if (cost < best_cost) {
      best_cost = cost;
      best_cand = cand;
      best_bin = bin;
    }
    const int heavy = cand.front();
    cand.erase(cand.begin());
    for (int c : children[static_cast<size_t>(heavy)]) cand.push_back(c);
  }
  if (best_cand.empty()) return out;
  out.owner.assign(static_cast<size_t>(ns), 0);
  for (size_t i = 0; i < best_cand.size(); ++i)
    for (int sn = first[static_cast<size_t>(best_cand[i])]; sn <= best_cand[i]; ++sn) out.owner[static_cast<size_t>(sn)] = static_cast<std::uint8_t>(1 + best_bin[i]);
  for (int sn = 0; sn < ns; ++sn) {
    const std::uint8_t o = out.owner[static_cast<size_t>(sn)];
    (o == 0 ? out.rest : out.group[o - 1]).push_back(sn);
  }
  return out;
}

}  // namespace wefm
