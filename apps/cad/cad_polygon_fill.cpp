// fill_polygon: ear clipping. An ear is a convex corner whose triangle holds no other corner of the
// polygon left; cutting it off keeps the rest simple.
#include "cad_polygon_fill.hpp"

#include <cmath>

namespace wefm_cad {

namespace {

using P = std::array<double, 2>;

double cross(const P& o, const P& a, const P& b) { return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]); }

bool inside(const P& p, const P& a, const P& b, const P& c) {
  return cross(a, b, p) >= 0 && cross(b, c, p) >= 0 && cross(c, a, p) >= 0;
}

// Where no corner is an ear (the polygon touches or crosses itself: the chord polygons of two edges
// closer than their sagitta), the corner whose triangle is the best-shaped, turning the right way if
// any does: the facets then cover the loop as a disk, folded where the chords cross.
size_t best_corner(const std::vector<P>& polygon, const std::vector<int>& ring) {
  const size_t m = ring.size();
  size_t best = 0;
  double best_shape = -HUGE_VAL;
  for (size_t i = 0; i < m; ++i) {
    const P& a = polygon[static_cast<size_t>(ring[(i + m - 1) % m])];
    const P& b = polygon[static_cast<size_t>(ring[i])];
    const P& c = polygon[static_cast<size_t>(ring[(i + 1) % m])];
    const double sq = std::hypot(b[0] - a[0], b[1] - a[1]) + std::hypot(c[0] - b[0], c[1] - b[1]) + std::hypot(a[0] - c[0], a[1] - c[1]);
    const double shape = sq > 0 ? cross(a, b, c) / (sq * sq) : 0;
    if (shape > best_shape) {
      best_shape = shape;
      best = i;
    }
  }
  return best;
}

}  // namespace

std::vector<std::array<int, 3>> fill_polygon(const std::vector<P>& polygon) {
  std::vector<std::array<int, 3>> out;
  const size_t n = polygon.size();
  if (n < 3) return out;
  double area = 0;
  for (size_t i = 0; i < n; ++i) area += cross({0, 0}, polygon[i], polygon[(i + 1) % n]);
  std::vector<int> ring;
  for (size_t i = 0; i < n; ++i) ring.push_back(static_cast<int>(area >= 0 ? i : n - 1 - i));
  while (ring.size() > 3) {
    const size_t m = ring.size();
    size_t ear = m;
    for (size_t i = 0; i < m && ear == m; ++i) {
      const P& a = polygon[static_cast<size_t>(ring[(i + m - 1) % m])];
      const P& b = polygon[static_cast<size_t>(ring[i])];
      const P& c = polygon[static_cast<size_t>(ring[(i + 1) % m])];
      if (!(cross(a, b, c) > 0)) continue;
      bool empty = true;
      for (size_t j = 0; j < m && empty; ++j) {
        if (j == i || j == (i + 1) % m || j == (i + m - 1) % m) continue;
        const P& p = polygon[static_cast<size_t>(ring[j])];
        if ((p == a) || (p == b) || (p == c)) continue;
        empty = !inside(p, a, b, c);
      }
      if (empty) ear = i;
    }
    if (ear == m) ear = best_corner(polygon, ring);
    out.push_back({ring[(ear + m - 1) % m], ring[ear], ring[(ear + 1) % m]});
    ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(ear));
  }
  out.push_back({ring[0], ring[1], ring[2]});
  return out;
}

}  // namespace wefm_cad
