#include "wefm/core/meshing/graded_spacing.hpp"

#include <algorithm>
#include <cmath>

#include "wefm/common/linear_size.hpp"

namespace wefm::meshing {

std::vector<double> graded_spacing(double length, double h, double s0, double s1, double g, Index min_count) {
  // The size is one of h, s0 + g s and s1 + g (L - s) on each piece between the points where
  // those lines cross.
  std::vector<double> cuts{0.0, length};
  if (g > 0)
    for (double c : {(h - s0) / g, length - (h - s1) / g, (s1 - s0 + g * length) / (2 * g)})
      if (c > 0 && c < length) cuts.push_back(c);
  std::sort(cuts.begin(), cuts.end());
  wefm_common::LinearSize size;
  for (size_t k = 0; k + 1 < cuts.size(); ++k) {
    const double a = cuts[k], b = cuts[k + 1];
    if (!(b > a)) continue;
    const double mid = 0.5 * (a + b);
    double c0 = h, c1 = 0.0;
    if (g > 0 && s0 + g * mid < c0) c0 = s0 + g * a, c1 = g;
    if (g > 0 && s1 + g * (length - mid) < c0 + c1 * (mid - a)) c0 = s1 + g * (length - a), c1 = -g;
    size.append(a, b, c0, c1);
  }
  const double total = size.total();
  const Index n = std::max<Index>(std::max<Index>(min_count, 1), static_cast<Index>(std::lround(total)));
  std::vector<double> out;
  out.reserve(static_cast<size_t>(n));
  for (Index k = 0; k < n; ++k) {
    const double phi = total * static_cast<double>(k) / static_cast<double>(n);
    out.push_back(size.empty() ? length * static_cast<double>(k) / static_cast<double>(n) : size.inverse(phi));
  }
  return out;
}

}  // namespace wefm::meshing
