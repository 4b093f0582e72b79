#include "wefm/core/meshing/size_field.hpp"

#include <algorithm>
#include <cmath>

namespace wefm::meshing {

SizeField::SizeField(const std::vector<LoopNodes>& loops, double h, double gradation) : h_(h), g_(std::max(gradation, 1e-6)) {
  double lmin = h;
  for (const LoopNodes& l : loops) {
    const size_t n = l.xyz.size();
    for (size_t k = 0; k < n; ++k) {
      const Vec3 &a = l.xyz[k], &b = l.xyz[(k + 1) % n];
      const double len = (b - a).norm();
      // Segments at h or longer never lower the size; the small margin keeps the near-h segments
      // that rounding of the edge discretisation leaves (h / 0.98) from becoming sources.
      if (!(len < 0.98 * h) || !(len > 0)) continue;
      src_.push_back({0.5 * (a + b), len});
      lmin = std::min(lmin, len);
    }
  }
  if (src_.empty()) return;
  reach_ = (h - lmin) / g_;
  Vec3 hi = Vec3::Constant(-1e300);
  lo_ = Vec3::Constant(1e300);
  for (const Source& s : src_) lo_ = lo_.cwiseMin(s.c), hi = hi.cwiseMax(s.c);
  cell_ = std::max(reach_, 1e-12 * std::max((hi - lo_).norm(), 1e-300));
  for (;;) {
    double total = 1;
    for (int k = 0; k < 3; ++k) {
      n_[k] = static_cast<int>((hi[k] - lo_[k]) / cell_) + 1;
      total *= n_[k];
    }
    if (total <= 4.0 * static_cast<double>(src_.size()) + 64) break;
    cell_ *= 1.5;
  }
  auto cell_id = [&](const Vec3& c) {
    size_t id = 0;
    for (int k = 2; k >= 0; --k) id = id * static_cast<size_t>(n_[k]) + static_cast<size_t>(std::clamp(static_cast<int>((c[k] - lo_[k]) / cell_), 0, n_[k] - 1));
    return id;
  };
  start_.assign(static_cast<size_t>(n_[0]) * static_cast<size_t>(n_[1]) * static_cast<size_t>(n_[2]) + 1, 0);
  for (const Source& s : src_) start_[cell_id(s.c) + 1]++;
  for (size_t k = 1; k < start_.size(); ++k) start_[k] += start_[k - 1];
  items_.resize(src_.size());
  std::vector<Index> fill(start_.begin(), start_.end() - 1);
  for (size_t i = 0; i < src_.size(); ++i) items_[static_cast<size_t>(fill[cell_id(src_[i].c)]++)] = static_cast<Index>(i);
}

bool SizeField::beyond(double d2, double gap) const {
  // True only where l + g sqrt(d2) >= l + gap however the terms round: the margin on the squared
  // reach is far above the few roundings between the two; tiny reaches (where squares lose
  // precision) are always measured.
  const double r = gap / g_;
  const double r2 = r * r;
  return r2 > 1e-250 && d2 > r2 * (1 + 1e-6);
}

double SizeField::at(const Vec3& x) const {
  double best = h_;
  if (src_.empty()) return best;
  int c[3];
  for (int k = 0; k < 3; ++k) {
    const double f = std::floor((x[k] - lo_[k]) / cell_);
    // A point more than one cell outside the sources' box is beyond every source's reach.
    if (f < -1 || f > n_[k]) return best;
    c[k] = static_cast<int>(f);
  }
  for (int z = std::max(0, c[2] - 1); z <= std::min(n_[2] - 1, c[2] + 1); ++z)
    for (int y = std::max(0, c[1] - 1); y <= std::min(n_[1] - 1, c[1] + 1); ++y)
      for (int xx = std::max(0, c[0] - 1); xx <= std::min(n_[0] - 1, c[0] + 1); ++xx) {
        const size_t id = (static_cast<size_t>(z) * static_cast<size_t>(n_[1]) + static_cast<size_t>(y)) * static_cast<size_t>(n_[0]) + static_cast<size_t>(xx);
        for (Index k = start_[id]; k < start_[id + 1]; ++k) {
          const Source& s = src_[static_cast<size_t>(items_[static_cast<size_t>(k)])];
          // l + g d >= l: a source no shorter than the best size cannot lower it.
          if (!(s.l < best)) continue;
          const double d2 = (x - s.c).squaredNorm();
          if (beyond(d2, best - s.l)) continue;
          best = std::min(best, s.l + g_ * std::sqrt(d2));
        }
      }
  return best;
}

}  // namespace wefm::meshing
