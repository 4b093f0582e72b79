#include "wefm/core/method/shape_barrier.hpp"

#include <algorithm>
#include <cmath>

namespace wefm {

namespace {

constexpr double kLo = 6.928203230275509;  // 4 sqrt(3)

double cross(Complex a, Complex b) { return a.real() * b.imag() - a.imag() * b.real(); }

}  // namespace

ShapeBarrier::ShapeBarrier(const Topology& tp, const Coefficients& c, double min_beta) {
  const size_t nt = tp.corner_use.size() / 3;
  lambda3d_.resize(nt);
  // A triangle of base b and altitude min_beta b has lambda at most 4 sqrt(3) (b^2 min_beta / 2) / (2 b^2).
  const double floor = kLo * 0.25 * min_beta;
  for (size_t t = 0; t < nt; ++t) {
    const double l0 = c.length[3 * t], l1 = c.length[3 * t + 1], l2 = c.length[3 * t + 2];
    const double sum = l0 * l0 + l1 * l1 + l2 * l2;
    lambda3d_[t] = std::max(sum > 0 ? kLo * c.tri_area[t] / sum : 0.0, floor);
  }
}

bool ShapeBarrier::row(size_t t, Complex a, Complex b, Complex c, double& r, std::array<Complex, 3>& l) const {
  const Complex p1 = b - a, p2 = c - a, p3 = c - b;
  const double A = 0.5 * cross(p1, p2);
  const double S = std::norm(p1) + std::norm(p2) + std::norm(p3);
  if (!(A > 0) || !(S > 0)) return false;  // flipped or collapsed: the line search's business
  const double q = kLo * A / S / lambda3d_[t];
  if (q >= kEps) return false;
  r = kGamma * (kEps / q - 1.0);
  // Real functionals as sum 2 Re(l dz): cross(dx, y) has l = i conj(y) / 2, d|e|^2 has l = conj(e).
  const Complex I(0, 1);
  const std::array<Complex, 3> lA = {-(I * std::conj(p2) / 4.0) + I * std::conj(p1) / 4.0, I * std::conj(p2) / 4.0, -I * std::conj(p1) / 4.0};
  const std::array<Complex, 3> lS = {-std::conj(p1) - std::conj(p2), std::conj(p1) - std::conj(p3), std::conj(p2) + std::conj(p3)};
  // dr/dq = -gamma eps / q^2; dq = 4 sqrt(3) (dA / S - A dS / S^2) / lambda_3d.
  const double f = -kGamma * kEps / (q * q) * kLo / lambda3d_[t];
  for (int k = 0; k < 3; ++k) l[static_cast<size_t>(k)] = f * (lA[static_cast<size_t>(k)] / S - A * lS[static_cast<size_t>(k)] / (S * S));
  return true;
}

}  // namespace wefm
