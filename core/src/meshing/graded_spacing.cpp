#include "wefm/core/meshing/graded_spacing.hpp"

#include <algorithm>
#include <cmath>

namespace wefm::meshing {

std::vector<double> graded_spacing(double length, double h, double s0, double s1, double g, Index min_count) {
  // size = c0 + c1 (s - a) on each piece [a, b] between the points where the three lines cross.
  struct Piece {
    double a, b, phi0, c0, c1;
    double integral(double s) const { return c1 == 0 ? (s - a) / c0 : std::log((c0 + c1 * (s - a)) / c0) / c1; }
  };
  std::vector<double> cuts{0.0, length};
  if (g > 0)
    for (double c : {(h - s0) / g, length - (h - s1) / g, (s1 - s0 + g * length) / (2 * g)})
      if (c > 0 && c < length) cuts.push_back(c);
  std::sort(cuts.begin(), cuts.end());
  std::vector<Piece> pieces;
  double total = 0;
  for (size_t k = 0; k + 1 < cuts.size(); ++k) {
    const double a = cuts[k], b = cuts[k + 1];
    if (!(b > a)) continue;
    const double mid = 0.5 * (a + b);
    Piece p{a, b, total, h, 0.0};
    if (g > 0 && s0 + g * mid < p.c0) p.c0 = s0 + g * a, p.c1 = g;
    if (g > 0 && s1 + g * (length - mid) < p.c0 + p.c1 * (mid - a)) p.c0 = s1 + g * (length - a), p.c1 = -g;
    total += p.integral(b);
    pieces.push_back(p);
  }
  const Index n = std::max<Index>(std::max<Index>(min_count, 1), static_cast<Index>(std::lround(total)));
  std::vector<double> out;
  out.reserve(static_cast<size_t>(n));
  size_t at = 0;
  for (Index k = 0; k < n; ++k) {
    const double phi = total * static_cast<double>(k) / static_cast<double>(n);
    while (at + 1 < pieces.size() && phi > pieces[at].phi0 + pieces[at].integral(pieces[at].b)) ++at;
    if (pieces.empty()) {
      out.push_back(length * static_cast<double>(k) / static_cast<double>(n));
      continue;
    }
    const Piece& p = pieces[at];
    const double t = std::clamp(phi - p.phi0, 0.0, p.integral(p.b));
    const double s = p.c1 == 0 ? p.a + p.c0 * t : p.a + p.c0 * (std::exp(p.c1 * t) - 1) / p.c1;
    out.push_back(std::clamp(s, p.a, p.b));
  }
  return out;
}

}  // namespace wefm::meshing
