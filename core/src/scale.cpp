#include "wefm/core/scale.hpp"

#include <cmath>

#include "wefm/core/energy.hpp"

namespace wefm {

double optimal_scale(const Topology& tp, const Coefficients& c, const VectorXc& z, double s, double k, Complex center) {
  if (s <= 0) return 1.0;
  (void)center;  // translation does not change the surface energy
  const std::vector<double> w = compute_weights(tp, c, k);
  // Residual at use i under scaling a: a P_i - a^(1-s) Q_i with P the rho-free part, Q the altitude part.
  std::vector<Complex> P(static_cast<size_t>(tp.use_count), 0.0), Q(static_cast<size_t>(tp.use_count), 0.0);
  for (size_t h = 0; h < w.size(); ++h) {
    const Index i = tp.corner_use[static_cast<size_t>(HalfEdges::prev(static_cast<Index>(h)))];
    const Index i1 = tp.corner_use[h], i2 = tp.corner_use[static_cast<size_t>(HalfEdges::next(static_cast<Index>(h)))];
    const Complex e = z[i2] - z[i1];
    const double d = std::abs(e);
    if (!(d > 0) || !(c.length[h] > 0)) continue;
    P[static_cast<size_t>(i)] += w[h] * (z[i] - z[i1] - c.alpha[h] * e);
    Q[static_cast<size_t>(i)] += w[h] * Complex(0, c.beta[h] * std::pow(c.length[h] / d, s)) * e;
  }
  double pp = 0, pq = 0, qq = 0;
  for (size_t i = 0; i < P.size(); ++i) {
    pp += std::norm(P[i]);
    pq += (std::conj(P[i]) * Q[i]).real();
    qq += std::norm(Q[i]);
  }
  if (!(pp > 0)) return 1.0;
  auto energy = [&](double a) { return a * a * pp - 2 * std::pow(a, 2 - s) * pq + std::pow(a, 2 - 2 * s) * qq; };
  // dE/da = 0  <=>  2 pp t^2 - 2 (2 - s) pq t + (2 - 2s) qq = 0 with t = a^s.
  const double A = 2 * pp, Bq = -2 * (2 - s) * pq, C = (2 - 2 * s) * qq;
  const double disc = Bq * Bq - 4 * A * C;
  double best = 1.0, best_e = energy(1.0);
  if (disc >= 0)
    for (double sign : {-1.0, 1.0}) {
      const double t = (-Bq + sign * std::sqrt(disc)) / (2 * A);
      if (t > 0) {
        const double a = std::pow(t, 1.0 / s);
        if (std::isfinite(a) && energy(a) < best_e) {
          best_e = energy(a);
          best = a;
        }
      }
    }
  return best;
}

}  // namespace wefm
