#include "wefm/core/meshing/mesh_quality.hpp"

#include <algorithm>
#include <cmath>

#include "wefm/common/element_corners.hpp"
#include "wefm/common/scaled_jacobian.hpp"

namespace wefm::meshing {

double scaled_jacobian(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) { return wefm_common::scaled_jacobian(a, b, c, d); }

double wiggle(const std::vector<Vec3>& x, const std::vector<Vec3>& nrm) {
  const size_t n = x.size() - 1;
  if (x.size() < 3) return 0;
  double mean = 0;
  for (size_t j = 1; j <= n; ++j) mean += (x[j] - x[j - 1]).norm();
  mean /= static_cast<double>(n);
  if (!(mean > 0)) return 0;
  double sum = 0;
  for (size_t j = 1; j < n; ++j) {
    Vec3 d = (x[j + 1] - x[j]) - (x[j] - x[j - 1]);
    d -= d.dot(nrm[j]) * nrm[j];
    sum += d.squaredNorm();
  }
  return sum / static_cast<double>(n) / (mean * mean);
}

void measure_quality(DomainMesh& m) {
  MeshReport& r = m.report;
  r.nodes = static_cast<std::int64_t>(m.uv.size());
  r.nodes_per_element = m.nodes_per_element;
  r.quads = 0;
  const size_t npe = static_cast<size_t>(m.nodes_per_element);
  r.elements = static_cast<std::int64_t>(m.elements.size() / npe);
  auto X = [&](size_t e, size_t k) -> const Vec3& { return m.xyz[static_cast<size_t>(m.elements[e * npe + k])]; };
  std::vector<double> lam;
  double sj_sum = 0, sj_min = 1, quad_area = 0, area = 0;
  auto tri_area = [&](const Vec3& a, const Vec3& b, const Vec3& c) { return 0.5 * (b - a).cross(c - a).norm(); };
  for (size_t e = 0; e < static_cast<size_t>(r.elements); ++e) {
    // A quad-dominant mesh's triangle: four nodes, the last -1.
    if (wefm_common::element_corners(&m.elements[e * npe], m.nodes_per_element) == 3) {
      lam.push_back(lo_lambda(X(e, 0), X(e, 1), X(e, 2)));
      area += tri_area(X(e, 0), X(e, 1), X(e, 2));
      continue;
    }
    const double sj = scaled_jacobian(X(e, 0), X(e, 1), X(e, 2), X(e, 3));
    sj_sum += sj, sj_min = std::min(sj_min, sj);
    r.quads++;
    // Quads also get Lo's lambda on the two triangles of their shorter diagonal.
    double a = 0;
    if ((X(e, 0) - X(e, 2)).norm() <= (X(e, 1) - X(e, 3)).norm()) {
      lam.push_back(lo_lambda(X(e, 0), X(e, 1), X(e, 2)));
      lam.push_back(lo_lambda(X(e, 0), X(e, 2), X(e, 3)));
      a = tri_area(X(e, 0), X(e, 1), X(e, 2)) + tri_area(X(e, 0), X(e, 2), X(e, 3));
    } else {
      lam.push_back(lo_lambda(X(e, 0), X(e, 1), X(e, 3)));
      lam.push_back(lo_lambda(X(e, 1), X(e, 2), X(e, 3)));
      a = tri_area(X(e, 0), X(e, 1), X(e, 3)) + tri_area(X(e, 1), X(e, 2), X(e, 3));
    }
    quad_area += a, area += a;
  }
  if (r.quads > 0) r.scaled_jacobian_min = sj_min, r.scaled_jacobian_mean = sj_sum / static_cast<double>(r.quads);
  r.quad_area_fraction = area > 0 ? quad_area / area : 0;
  if (!lam.empty()) {
    double logsum = 0, mn = 1;
    size_t below = 0;
    for (double l : lam) {
      logsum += std::log(std::max(l, 1e-300));
      mn = std::min(mn, l);
      below += l < 0.6 ? 1 : 0;
    }
    r.lambda_mesh = std::exp(logsum / static_cast<double>(lam.size()));
    r.lambda_min = mn;
    r.fraction_below_0_6 = static_cast<double>(below) / static_cast<double>(lam.size());
  }
  double wmax = 0, wsum = 0;
  for (const auto& rail : m.rails) {
    std::vector<Vec3> x, n;
    for (Index i : rail) x.push_back(m.xyz[static_cast<size_t>(i)]), n.push_back(m.normal[static_cast<size_t>(i)]);
    const double w = wiggle(x, n);
    wmax = std::max(wmax, w), wsum += w;
  }
  r.wiggle_max = wmax;
  r.wiggle_mean = m.rails.empty() ? 0 : wsum / static_cast<double>(m.rails.size());
}

}  // namespace wefm::meshing
