#include "wefm/core/energy.hpp"

#include <cmath>

namespace wefm {

std::vector<Complex> compute_sigma(const Coefficients& c, const std::vector<double>& rho, double s) {
  std::vector<Complex> sigma(c.alpha.size());
  const bool use_rho = s != 0.0 && !rho.empty();
  for (size_t h = 0; h < sigma.size(); ++h) sigma[h] = Complex(c.alpha[h], c.beta[h] * (use_rho ? std::pow(rho[h], s) : 1.0));
  return sigma;
}

std::vector<double> compute_rho(const Topology& tp, const Coefficients& c, const VectorXc& z) {
  std::vector<double> rho(c.length.size(), 1.0);
  for (size_t h = 0; h < rho.size(); ++h) {
    const Index u1 = tp.corner_use[h], u2 = tp.corner_use[static_cast<size_t>(HalfEdges::next(static_cast<Index>(h)))];
    const double d = std::abs(z[u2] - z[u1]);
    if (d > 0 && c.length[h] > 0) rho[h] = c.length[h] / d;
  }
  return rho;
}

std::vector<double> compute_weights(const Topology& tp, const Coefficients& c, double k) {
  const size_t nh = c.alpha.size();
  std::vector<double> inv_sum(static_cast<size_t>(tp.use_count), 0.0);
  for (size_t h = 0; h < nh; ++h) inv_sum[static_cast<size_t>(tp.corner_use[static_cast<size_t>(HalfEdges::prev(static_cast<Index>(h)))])] += 1.0 / c.beta[h];
  std::vector<double> w(nh);
  for (size_t h = 0; h < nh; ++h)
    w[h] = (1.0 / c.beta[h]) * std::pow(inv_sum[static_cast<size_t>(tp.corner_use[static_cast<size_t>(HalfEdges::prev(static_cast<Index>(h)))])], -k);
  return w;
}

SpMatC assemble_surface_operator(const Topology& tp, const Coefficients& c, const std::vector<Complex>& sigma, double k, Residual form) {
  const Index n = tp.use_count;
  const size_t nh = c.alpha.size();
  const std::vector<double> w = compute_weights(tp, c, k);
  std::vector<Eigen::Triplet<Complex>> trip;
  trip.reserve(nh * 3);
  if (form == Residual::PerHalfEdge) {
    for (size_t h = 0; h < nh; ++h) {
      const Index i = tp.corner_use[static_cast<size_t>(HalfEdges::prev(static_cast<Index>(h)))];
      const Index i1 = tp.corner_use[h], i2 = tp.corner_use[static_cast<size_t>(HalfEdges::next(static_cast<Index>(h)))];
      const double sw = std::sqrt(w[h]);
      const Index r = static_cast<Index>(h);
      trip.emplace_back(r, i, Complex(sw, 0));
      trip.emplace_back(r, i1, -sw * (1.0 - sigma[h]));
      trip.emplace_back(r, i2, -sw * sigma[h]);
    }
    SpMatC A(static_cast<Index>(nh), n);
    A.setFromTriplets(trip.begin(), trip.end());
    return A;
  }
  for (size_t h = 0; h < nh; ++h) {
    const Index i = tp.corner_use[static_cast<size_t>(HalfEdges::prev(static_cast<Index>(h)))];
    const Index i1 = tp.corner_use[h], i2 = tp.corner_use[static_cast<size_t>(HalfEdges::next(static_cast<Index>(h)))];
    trip.emplace_back(i, i, Complex(w[h], 0));
    trip.emplace_back(i, i1, -w[h] * (1.0 - sigma[h]));
    trip.emplace_back(i, i2, -w[h] * sigma[h]);
  }
  SpMatC A(n, n);
  A.setFromTriplets(trip.begin(), trip.end());
  return A;
}

SpMatC assemble_boundary_operator(const TriMesh& m, const Topology& tp, const Coefficients& c, double mu, double unwind) {
  const Index n = tp.use_count;
  std::vector<Eigen::Triplet<Complex>> trip;
  Index row = 0;
  const double inv = 1.0 / c.length_scale;
  auto pos = [&](Index u) -> const Vec3& { return m.vertices[static_cast<size_t>(tp.use_vertex[static_cast<size_t>(u)])]; };
  for (size_t d = 0; d < tp.loop_uses.size(); ++d) {
    const auto& lu = tp.loop_uses[d];
    const size_t nl = lu.size();
    if (nl < 3 || mu <= 0) continue;
    std::vector<double> seg(nl);  // 3D length of segment j -> j+1 (normalised)
    for (size_t j = 0; j < nl; ++j) seg[j] = (pos(lu[(j + 1) % nl]) - pos(lu[j])).norm() * inv;
    // Goal turning angle pi - theta, theta the face's 3D angle at the use. Unwinding: gentle turns
    // (below 30 degrees) aim at a fraction of their 3D value, corners keep theirs, so long curved
    // sides straighten.
    std::vector<double> turn(nl);
    double sum = 0, len = 0;
    for (size_t j = 0; j < nl; ++j) {
      turn[j] = kPi - c.use_angle[static_cast<size_t>(lu[j])];
      if (unwind < 1.0 && std::abs(turn[j]) < kPi / 6) turn[j] *= unwind;
      sum += turn[j];
      len += 0.5 * (seg[(j + nl - 1) % nl] + seg[j]);
    }
    // A closed planar loop turns by exactly +2 pi (outer, counter-clockwise) or -2 pi (inner). The 3D
    // goals sum to that only on developable faces (the rest is the enclosed Gaussian curvature): on
    // an uncut cylinder both loops are geodesics whose goals sum to 0, and the term folded the inner
    // loop into a straight segment. The difference is spread over the loop by segment length.
    const double target = (static_cast<Index>(d) == tp.outer_loop ? 2.0 : -2.0) * kPi;
    const double per_length = len > 0 ? (target - sum) / len : 0.0;
    for (size_t j = 0; j < nl; ++j) {
      const Index up = lu[(j + nl - 1) % nl], u = lu[j], un = lu[(j + 1) % nl];
      const double Lm = seg[(j + nl - 1) % nl], Lp = seg[j], lbar = 0.5 * (Lm + Lp);
      if (!(lbar > 0)) continue;
      // p = 0 exactly when the UV corner turns by the goal and its two segments have the 3D ratio.
      const double phi = 0.5 * (turn[j] + per_length * lbar);
      const double scale = std::sqrt(mu / lbar);
      const Complex cm = scale * (Lp / lbar) * std::polar(1.0, phi), cp = scale * (Lm / lbar) * std::polar(1.0, -phi);
      trip.emplace_back(row, up, cm);
      trip.emplace_back(row, un, cp);
      trip.emplace_back(row, u, -(cm + cp));
      ++row;
    }
  }
  SpMatC B(row, n);
  B.setFromTriplets(trip.begin(), trip.end());
  return B;
}

SpMatC assemble_energy(const SpMatC& A, const SpMatC* B) {
  SpMatC K = SpMatC(A.adjoint()) * A;
  if (B && B->nonZeros()) K += SpMatC(B->adjoint()) * (*B);
  K.makeCompressed();
  return K;
}

double energy_value(const SpMatC& A, const SpMatC* B, const VectorXc& z) {
  double e = (A * z).squaredNorm();
  if (B && B->rows()) e += ((*B) * z).squaredNorm();
  return e;
}

}  // namespace wefm
