#pragma once
// Lo's triangle quality, the measure every mesh report of the tool gives: 4 sqrt(3) area / sum of
// squared edge lengths, 1 for an equilateral triangle, 0 for one without area.
#include <cmath>

namespace wefm_cli {

inline double lo_lambda(const double* a, const double* b, const double* c) {
  double e1[3], e2[3], e3[3];
  for (int i = 0; i < 3; ++i) {
    e1[i] = b[i] - a[i];
    e2[i] = c[i] - a[i];
    e3[i] = c[i] - b[i];
  }
  const double cx = e1[1] * e2[2] - e1[2] * e2[1], cy = e1[2] * e2[0] - e1[0] * e2[2], cz = e1[0] * e2[1] - e1[1] * e2[0];
  const double area = 0.5 * std::sqrt(cx * cx + cy * cy + cz * cz);
  double sq = 0;
  for (int i = 0; i < 3; ++i) sq += e1[i] * e1[i] + e2[i] * e2[i] + e3[i] * e3[i];
  return sq > 0 ? 4.0 * std::sqrt(3.0) * area / sq : 0.0;
}

}  // namespace wefm_cli
