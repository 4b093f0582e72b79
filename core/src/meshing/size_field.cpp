#include "wefm/core/meshing/size_field.hpp"

#include <algorithm>
#include <cmath>

namespace wefm::meshing {

SizeField::SizeField(const std::vector<LoopNodes>& loops, double h, double gradation) : h_(h), g_(std::max(gradation, 1e-6)) {
  for (const LoopNodes& l : loops) {
    const size_t n = l.xyz.size();
    for (size_t k = 0; k < n; ++k) {
      const Vec3 &a = l.xyz[k], &b = l.xyz[(k + 1) % n];
      const double len = (b - a).norm();
      // Segments at h or longer never lower the size; the small margin keeps the near-h segments
      // that rounding of the edge discretisation leaves (h / 0.98) from becoming sources.
      if (!(len < 0.98 * h) || !(len > 0)) continue;
      src_.push_back({0.5 * (a + b), len});
    }
  }
  if (src_.empty()) return;
  nodes_.reserve(4 * src_.size() / kLeaf + 4);
  build(0, static_cast<Index>(src_.size()));
}

Index SizeField::build(Index first, Index last) {
  Node n{Vec3::Constant(1e300), Vec3::Constant(-1e300), 1e300, first, last, -1, -1};
  for (Index k = first; k < last; ++k) {
    const Source& s = src_[static_cast<size_t>(k)];
    n.lo = n.lo.cwiseMin(s.c), n.hi = n.hi.cwiseMax(s.c), n.lmin = std::min(n.lmin, s.l);
  }
  const Index id = static_cast<Index>(nodes_.size());
  nodes_.push_back(n);
  if (last - first <= kLeaf) return id;
  // Split at the median along the box's longest side.
  int axis = 0;
  (n.hi - n.lo).maxCoeff(&axis);
  const Index mid = first + (last - first) / 2;
  std::nth_element(src_.begin() + first, src_.begin() + mid, src_.begin() + last,
                   [axis](const Source& a, const Source& b) { return a.c[axis] < b.c[axis]; });
  const Index left = build(first, mid);
  const Index right = build(mid, last);
  nodes_[static_cast<size_t>(id)].left = left;
  nodes_[static_cast<size_t>(id)].right = right;
  return id;
}

double SizeField::bound(const Node& n, const Vec3& x) const {
  double d2 = 0;
  for (int k = 0; k < 3; ++k) {
    const double d = std::max({0.0, n.lo[k] - x[k], x[k] - n.hi[k]});
    d2 += d * d;
  }
  // Shrunk a little below the box's distance, so that rounding never puts the bound above the value
  // l + g |x - c| of a source in the box: a box is skipped only when none of its sources can lower
  // the size, and the field is the brute-force minimum bit for bit.
  return n.lmin + g_ * std::sqrt(d2 * (1 - 1e-9));
}

void SizeField::visit(Index node, const Vec3& x, double& best) const {
  const Node& n = nodes_[static_cast<size_t>(node)];
  if (n.left < 0) {
    for (Index k = n.first; k < n.last; ++k) {
      const Source& s = src_[static_cast<size_t>(k)];
      if (!(s.l < best)) continue;
      best = std::min(best, s.l + g_ * std::sqrt((x - s.c).squaredNorm()));
    }
    return;
  }
  // The nearer box first: its sources lower `best`, and the other box may then be skipped.
  Index a = n.left, b = n.right;
  double ba = bound(nodes_[static_cast<size_t>(a)], x), bb = bound(nodes_[static_cast<size_t>(b)], x);
  if (bb < ba) std::swap(a, b), std::swap(ba, bb);
  if (ba < best) visit(a, x, best);
  if (bb < best) visit(b, x, best);
}

double SizeField::at(const Vec3& x) const {
  double best = h_;
  if (nodes_.empty() || !(bound(nodes_[0], x) < best)) return best;
  visit(0, x, best);
  return best;
}

}  // namespace wefm::meshing
