#include "wefm/core/gauss_newton.hpp"

#include <Eigen/Dense>
#include <array>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <cstdio>
#include <cstdlib>

#include "wefm/core/energy.hpp"
#include "wefm/core/error.hpp"

namespace wefm {

namespace {

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

// Real 2x2 block (row-major) of dz -> l dz + m conj(dz) acting on (Re dz, Im dz).
void real_block(const Entry& e, double* J) {
  J[0] = e.l.real() + e.m.real();
  J[1] = -e.l.imag() + e.m.imag();
  J[2] = e.l.imag() + e.m.imag();
  J[3] = e.l.real() - e.m.real();
}

void add_entry(Entry* es, int& ne, Index use, Complex l, Complex m) {
  for (int j = 0; j < ne; ++j)
    if (es[j].use == use) {
      es[j].l += l;
      es[j].m += m;
      return;
    }
  es[ne++] = {use, l, m};
}

}  // namespace

GaussNewton::GaussNewton(const Topology& tp, const Coefficients& c, const SpMatC* B, double k, Residual form, SpMatC K,
                         const SeamSubstitution& sub, std::vector<LinearRow> rows, Backend backend, double min_beta)
    : tp_(tp), c_(c), B_(B), form_(form), w_(compute_weights(tp, c, k)), sub_(sub), barrier_(tp, c, min_beta), rows_(std::move(rows)),
      own_chol_(backend) {
  const Index n = tp.use_count;
  K.makeCompressed();
  // H_'s pattern: each entry of K becomes a 2x2 block, written column by column in place (the
  // triplet route held three copies at once and set the peak memory of the whole solve).
  H_.resize(2 * n, 2 * n);
  H_.resizeNonZeros(4 * K.nonZeros());
  int* outer = H_.outerIndexPtr();
  int* inner = H_.innerIndexPtr();
  outer[0] = 0;
  for (Index col = 0; col < K.outerSize(); ++col) {
    const int begin = K.outerIndexPtr()[col], end = K.outerIndexPtr()[col + 1];
    for (int b = 0; b < 2; ++b) {
      int pos = outer[2 * col + b];
      for (int v = begin; v < end; ++v) {
        inner[pos++] = 2 * K.innerIndexPtr()[v];
        inner[pos++] = 2 * K.innerIndexPtr()[v] + 1;
      }
      outer[2 * col + b + 1] = pos;
    }
  }
  std::fill(H_.valuePtr(), H_.valuePtr() + H_.nonZeros(), 0.0);
  Kc_ = std::move(K);
  if (B_) B_rows_ = *B_;
  if (form == Residual::PerUse) {
    // Rows per use: the half-edges opposite each use.
    opposite_.assign(static_cast<size_t>(n), {});
    for (size_t h = 0; h < c.alpha.size(); ++h)
      opposite_[static_cast<size_t>(tp.corner_use[static_cast<size_t>(HalfEdges::prev(static_cast<Index>(h)))])].push_back(h);
  }
  identity_ = sub.reduced == n;
  if (identity_)
    for (Index u = 0; u < n; ++u) identity_ = identity_ && sub.use_to_reduced[static_cast<size_t>(u)] == u;
  if (!identity_) {
    std::vector<Eigen::Triplet<double>> pt;
    for (Index col = 0; col < sub.P.outerSize(); ++col)
      for (SpMatC::InnerIterator it(sub.P, col); it; ++it) {
        const Complex v = it.value();
        const Index r = static_cast<Index>(it.row());
        pt.emplace_back(2 * r, 2 * col, v.real());
        pt.emplace_back(2 * r, 2 * col + 1, -v.imag());
        pt.emplace_back(2 * r + 1, 2 * col, v.imag());
        pt.emplace_back(2 * r + 1, 2 * col + 1, v.real());
      }
    P_real_.resize(2 * n, 2 * sub.reduced);
    P_real_.setFromTriplets(pt.begin(), pt.end());
    P_real_.makeCompressed();
  }
}

template <class F>
void GaussNewton::for_each_row(const VectorXc& z, double s, F&& f) const {
  for_each_row_split(z, s, [&](Complex p, Complex q, const Entry* es, int ne) { f(p - q, es, ne); });
  // The shape barrier is scale-free: it belongs here and not in the split rows that rescale uses.
  std::array<Complex, 3> l;
  double r = 0;
  Entry es[3];
  for (size_t t = 0; t < barrier_.triangles(); ++t) {
    const Index a = tp_.corner_use[3 * t], b = tp_.corner_use[3 * t + 1], c = tp_.corner_use[3 * t + 2];
    if (!barrier_.row(t, z[a], z[b], z[c], r, l)) continue;
    es[0] = {a, l[0], std::conj(l[0])};
    es[1] = {b, l[1], std::conj(l[1])};
    es[2] = {c, l[2], std::conj(l[2])};
    f(Complex(r, 0), es, 3);
  }
}

template <class F>
void GaussNewton::for_each_row_split(const VectorXc& z, double s, F&& f) const {
  const size_t nh = c_.alpha.size();
  // One half-edge's prediction error sw (z_i - z1 - alpha d - g(d)), g(d) = i beta L^s |d|^-s d.
  // p: the part of degree 1 in z, q: the altitude term g of degree 1 - s.
  auto half_edge = [&](size_t h, double sw, Complex& p, Complex& q, Entry* es, int& ne) {
    const Index hi = static_cast<Index>(h);
    const Index i = tp_.corner_use[static_cast<size_t>(HalfEdges::prev(hi))];
    const Index i1 = tp_.corner_use[h], i2 = tp_.corner_use[static_cast<size_t>(HalfEdges::next(hi))];
    const Complex d = z[i2] - z[i1];
    const double ad = std::max(std::abs(d), 1e-12);
    const Complex u = std::abs(d) > 0 ? d / std::abs(d) : Complex(1, 0);
    const double mag = c_.beta[h] * (s == 0 ? 1.0 : std::pow(c_.length[h] / ad, s));
    const Complex g = Complex(0, mag) * d;
    const Complex lg = Complex(0, mag * (1.0 - 0.5 * s)), mg = Complex(0, -mag * 0.5 * s) * u * u;
    p += sw * (z[i] - z[i1] - c_.alpha[h] * d);
    q += sw * g;
    add_entry(es, ne, i, sw, 0.0);
    add_entry(es, ne, i1, sw * (-(1.0 - c_.alpha[h]) + lg), sw * mg);
    add_entry(es, ne, i2, sw * (-c_.alpha[h] - lg), -sw * mg);
  };
  Entry es[64];
  if (form_ == Residual::PerHalfEdge) {
    for (size_t h = 0; h < nh; ++h) {
      Complex p{0, 0}, q{0, 0};
      int ne = 0;
      half_edge(h, std::sqrt(w_[h]), p, q, es, ne);
      f(p, q, es, ne);
    }
  } else {
    std::vector<Entry> big;
    for (const auto& hs : opposite_) {
      if (hs.empty()) continue;
      Complex p{0, 0}, q{0, 0};
      int ne = 0;
      big.assign(2 * hs.size() + 1, Entry{});
      for (size_t h : hs) half_edge(h, w_[h], p, q, big.data(), ne);
      f(p, q, big.data(), ne);
    }
  }
}

void GaussNewton::add_block(Index a, Index b, const double* Ja, const double* Jb, const Entry& ea, const Entry& eb) {
  // Kc(a, b) += conj(l_a) l_b + m_a conj(m_b): |sum l dz|^2 + |sum m conj(dz)|^2, the real form
  // without the cross terms between the complex-linear and anti-linear parts (small below s = 2).
  {
    const int* begin = Kc_.innerIndexPtr() + Kc_.outerIndexPtr()[b];
    const int* end = Kc_.innerIndexPtr() + Kc_.outerIndexPtr()[b + 1];
    const int* p = std::lower_bound(begin, end, static_cast<int>(a));
    if (p == end || *p != a) fail(Errc::internal, "Gauss-Newton block outside the energy pattern");
    Kc_.valuePtr()[p - Kc_.innerIndexPtr()] += std::conj(ea.l) * eb.l + ea.m * std::conj(eb.m);
  }
  // H(a, b) += Ja^T Jb
  for (int cb = 0; cb < 2; ++cb) {
    const Index col = 2 * b + cb;
    const int* begin = H_.innerIndexPtr() + H_.outerIndexPtr()[col];
    const int* end = H_.innerIndexPtr() + H_.outerIndexPtr()[col + 1];
    const int* p = std::lower_bound(begin, end, 2 * a);
    if (p == end || *p != 2 * a) fail(Errc::internal, "Gauss-Newton block outside the energy pattern");
    double* v = H_.valuePtr() + (p - H_.innerIndexPtr());
    for (int ra = 0; ra < 2; ++ra) v[ra] += Ja[0 * 2 + ra] * Jb[0 * 2 + cb] + Ja[1 * 2 + ra] * Jb[1 * 2 + cb];
  }
}

void GaussNewton::linearise(const VectorXc& z, double s, Eigen::VectorXd& g, double& energy) {
  const Index n = tp_.use_count;
  std::fill(H_.valuePtr(), H_.valuePtr() + H_.nonZeros(), 0.0);
  std::fill(Kc_.valuePtr(), Kc_.valuePtr() + Kc_.nonZeros(), Complex(0, 0));
  g.setZero(2 * n);
  energy = 0;
  std::vector<double> J;
  auto accumulate = [&](Complex r, const Entry* es, int ne) {
    energy += std::norm(r);
    J.resize(static_cast<size_t>(4 * ne));
    for (int a = 0; a < ne; ++a) {
      real_block(es[a], &J[static_cast<size_t>(4 * a)]);
      const double* Ja = &J[static_cast<size_t>(4 * a)];
      g[2 * es[a].use] += Ja[0] * r.real() + Ja[2] * r.imag();
      g[2 * es[a].use + 1] += Ja[1] * r.real() + Ja[3] * r.imag();
    }
    for (int a = 0; a < ne; ++a)
      for (int b = 0; b < ne; ++b) add_block(es[a].use, es[b].use, &J[static_cast<size_t>(4 * a)], &J[static_cast<size_t>(4 * b)], es[a], es[b]);
  };
  for_each_row(z, s, accumulate);
  if (B_) {
    // The boundary term is complex-linear: rows of B as they are.
    const auto& Br = B_rows_;
    Entry es[8];
    for (Index row = 0; row < Br.rows(); ++row) {
      Complex r{0, 0};
      int ne = 0;
      for (Eigen::SparseMatrix<Complex, Eigen::RowMajor, int>::InnerIterator it(Br, row); it; ++it) {
        r += it.value() * z[it.col()];
        if (ne < 8) add_entry(es, ne, static_cast<Index>(it.col()), it.value(), 0.0);
      }
      accumulate(r, es, ne);
    }
  }
}

double GaussNewton::energy(const VectorXc& z, double s) const {
  double e = 0;
  for_each_row(z, s, [&](Complex r, const Entry*, int) { e += std::norm(r); });
  if (B_) e += ((*B_) * z).squaredNorm();
  return e;
}

double GaussNewton::rescale(VectorXc& z, double s) const {
  // E(a) = a^2 P - 2 a^(2-s) Q + a^(2-2s) R; dE/da = 0 <=> P t^2 - (2-s) Q t + (1-s) R = 0, t = a^s.
  double P = 0, Q = 0, R = 0;
  for_each_row_split(z, s, [&](Complex p, Complex q, const Entry*, int) {
    P += std::norm(p);
    Q += (std::conj(p) * q).real();
    R += std::norm(q);
  });
  if (B_) P += ((*B_) * z).squaredNorm();
  if (!(P > 0) || s <= 0) return 1.0;
  const double b = -(2 - s) * Q, c = (1 - s) * R, disc = b * b - 4 * P * c;
  if (disc < 0) return 1.0;
  const double t = (-b + std::sqrt(disc)) / (2 * P);  // the larger root: the local minimum
  const double a = t > 0 ? std::pow(t, 1.0 / s) : 1.0;
  if (!std::isfinite(a) || !(a > 0)) return 1.0;
  z = ((z.array() - center_) * a + center_).matrix();
  return a;
}

bool GaussNewton::solve_step(const SpMatR& H, const Eigen::VectorXd& shift, const Eigen::VectorXd& g, const Eigen::MatrixXd& C,
                             Eigen::VectorXd& delta) {
  // Projected conjugate gradients on (H + diag(shift)) delta = -g with C delta = 0, preconditioned
  // by a complex factorisation of the complex-linear part of an earlier Gauss-Newton matrix (the
  // constraint preconditioner keeps every iterate in the null space of C). The real 2n matrix
  // itself was factorised before: measured at 1M triangles, s = 1, its factor took the peak from
  // 1.35 GB (s = 0) to 3.1 GB; the complex one is the s = 0 factor's storage, refactorised in
  // place, and costs 4-8 CG iterations per step where the real one cost 1-3.
  const Index nr = static_cast<Index>(H.rows());
  auto refactor = [&] {
    auto shift_of = [&](Index i) { return 0.5 * (shift[2 * i] + shift[2 * i + 1]); };
    if (!p_of_.empty()) {
      std::fill(Kpp_.valuePtr(), Kpp_.valuePtr() + Kpp_.nonZeros(), Complex(0, 0));
      for (Index v = 0; v < Kc_.nonZeros(); ++v)
        if (kc_to_pp_[static_cast<size_t>(v)] >= 0) Kpp_.valuePtr()[kc_to_pp_[static_cast<size_t>(v)]] = Kc_.valuePtr()[v];
      for (Index u = 0; u < nr / 2; ++u) {
        const Index pu = p_of_[static_cast<size_t>(u)];
        if (pu >= 0) Kpp_.coeffRef(pu, pu) += shift_of(u);
      }
      chol_->factorize(Kpp_);
      Eigen::MatrixXcd Kpx = Eigen::MatrixXcd::Zero(Kpp_.rows(), 2);
      for (const SplitEntry& e : px_entries_) Kpx(e.p, e.x) = Kc_.valuePtr()[e.value];
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) Sx_(i, j) = Kc_.coeff(split_[i], split_[j]) + (i == j ? shift_of(split_[i]) : 0.0);
      Wx_ = chol_->solve(Kpx);
      Sx_ -= Kpx.adjoint() * Wx_;
    } else {
      SpMatC Kd = identity_ ? Kc_ : SpMatC(sub_.P.adjoint() * Kc_ * sub_.P);
      for (Index i = 0; i < nr / 2; ++i) Kd.coeffRef(i, i) += shift_of(i);
      chol_->factorize(Kd);
    }
    factored_ = true;
  };
  // Refactorise when the last step needed many iterations (a factorisation costs about ten
  // solves at 1M triangles). A count, not a timing: results must not depend on machine load.
  bool fresh = false;
  if (!factored_ || last_pcg_ > kMaxStaleIterations) {
    refactor();
    fresh = true;
  }
  Eigen::MatrixXd W;
  Eigen::FullPivLU<Eigen::MatrixXd> S;
  auto project = [&] {
    if (C.rows() == 0) return;
    W = precondition(C.transpose());
    S.compute(C * W);
  };
  project();
  for (;;) {
    auto precondition = [&](const Eigen::VectorXd& r) {
      Eigen::VectorXd y = this->precondition(r);
      if (C.rows() > 0) y -= W * S.solve(C * y);
      return y;
    };
    auto apply = [&](const Eigen::VectorXd& p) { return Eigen::VectorXd(H * p + shift.cwiseProduct(p)); };
    delta.setZero(nr);
    last_pcg_ = 0;
    Eigen::VectorXd r = -g, zr = precondition(r), p = zr;
    double rz = r.dot(zr);
    const double rz0 = rz;
    const double target = kCgTolerance * rz0;
    bool converged = rz0 <= 0;
    for (int it = 0; it < kMaxCgIterations && !converged; ++it) {
      const Eigen::VectorXd q = apply(p);
      const double pq = p.dot(q);
      if (!(pq > 0)) break;
      const double a = rz / pq;
      delta += a * p;
      r -= a * q;
      zr = precondition(r);
      const double rz_new = r.dot(zr);
      ++pcg_iterations_;
      last_pcg_ = it + 1;
      converged = !(rz_new > target);
      p = zr + (rz_new / rz) * p;
      rz = rz_new;
    }
    if (!delta.allFinite()) delta.setZero(nr);
    if (converged) return true;
    // Every CG iterate lowers the quadratic model, so an unfinished one is still a descent
    // direction (the line search sizes it); a stale factor gets one refactorisation first.
    if (fresh) return delta.squaredNorm() > 0;
    refactor();
    fresh = true;
    project();
  }
}

bool GaussNewton::share_factor(SparseCholesky& chol, Index x0, Index x1) {
  if (!identity_) return false;
  const Index n = tp_.use_count;
  chol_ = &chol;
  split_[0] = x0;
  split_[1] = x1;
  p_of_.assign(static_cast<size_t>(n), -1);
  Index k = 0;
  for (Index u = 0; u < n; ++u)
    if (u != x0 && u != x1) p_of_[static_cast<size_t>(u)] = k++;
  // The pattern PartitionedKKT::set_matrix gave K_PP, built the same way (triplets of K's pattern).
  std::vector<Eigen::Triplet<Complex>> pp;
  pp.reserve(static_cast<size_t>(Kc_.nonZeros()));
  for (Index c = 0; c < Kc_.outerSize(); ++c)
    for (SpMatC::InnerIterator it(Kc_, c); it; ++it) {
      const Index pr = p_of_[static_cast<size_t>(it.row())], pc = p_of_[static_cast<size_t>(c)];
      if (pr >= 0 && pc >= 0) pp.emplace_back(pr, pc, Complex(1, 0));
    }
  Kpp_.resize(n - 2, n - 2);
  Kpp_.setFromTriplets(pp.begin(), pp.end());
  Kpp_.makeCompressed();
  kc_to_pp_.assign(static_cast<size_t>(Kc_.nonZeros()), -1);
  for (Index c = 0; c < Kc_.outerSize(); ++c)
    for (Index v = Kc_.outerIndexPtr()[c]; v < Kc_.outerIndexPtr()[c + 1]; ++v) {
      const Index pr = p_of_[static_cast<size_t>(Kc_.innerIndexPtr()[v])], pc = p_of_[static_cast<size_t>(c)];
      if (pc < 0 && pr >= 0) px_entries_.push_back({v, pr, static_cast<Index>(c == x0 ? 0 : 1)});
      if (pr < 0 || pc < 0) continue;
      const int* begin = Kpp_.innerIndexPtr() + Kpp_.outerIndexPtr()[pc];
      const int* end = Kpp_.innerIndexPtr() + Kpp_.outerIndexPtr()[pc + 1];
      kc_to_pp_[static_cast<size_t>(v)] = std::lower_bound(begin, end, static_cast<int>(pr)) - Kpp_.innerIndexPtr();
    }
  return true;
}

Eigen::MatrixXd GaussNewton::precondition(const Eigen::MatrixXd& r) {
  const Index n = r.rows() / 2;
  auto at = [&](Index k, Index j) { return Complex(r(2 * k, j), r(2 * k + 1, j)); };
  Eigen::MatrixXcd x;
  if (!p_of_.empty()) {
    Eigen::MatrixXcd b(n - 2, r.cols());
    for (Index j = 0; j < r.cols(); ++j)
      for (Index k = 0; k < n; ++k)
        if (p_of_[static_cast<size_t>(k)] >= 0) b(p_of_[static_cast<size_t>(k)], j) = at(k, j);
    // [K_PP K_PX; K_XP K_XX] x = b by block elimination: y = K_PP^{-1} b_P,
    // x_X = S^{-1} (b_X - K_PX^H y), x_P = y - W x_X.
    Eigen::MatrixXcd xp = chol_->solve(b);
    Eigen::MatrixXcd bx(2, r.cols());
    for (Index j = 0; j < r.cols(); ++j)
      for (int s = 0; s < 2; ++s) bx(s, j) = at(split_[s], j);
    // K_PX^H y = W^H K_PP y = W^H b_P (K_PP Hermitian): no product with K_PX needed.
    const Eigen::MatrixXcd xx = Sx_.fullPivLu().solve(bx - Wx_.adjoint() * b);
    xp -= Wx_ * xx;
    x.resize(n, r.cols());
    for (Index j = 0; j < r.cols(); ++j) {
      for (Index k = 0; k < n; ++k)
        if (p_of_[static_cast<size_t>(k)] >= 0) x(k, j) = xp(p_of_[static_cast<size_t>(k)], j);
      for (int s = 0; s < 2; ++s) x(split_[s], j) = xx(s, j);
    }
  } else {
    Eigen::MatrixXcd b(n, r.cols());
    for (Index j = 0; j < r.cols(); ++j)
      for (Index k = 0; k < n; ++k) b(k, j) = at(k, j);
    x = chol_->solve(b);
  }
  Eigen::MatrixXd out(r.rows(), r.cols());
  for (Index j = 0; j < r.cols(); ++j)
    for (Index k = 0; k < n; ++k) {
      out(2 * k, j) = x(k, j).real();
      out(2 * k + 1, j) = x(k, j).imag();
    }
  return out;
}

double GaussNewton::first_flip(const VectorXc& z, const VectorXc& dz) const {
  // Twice the signed area of a triangle along z + t dz is A0 + A1 t + A2 t^2; for each triangle
  // positive now, the smallest t > 0 where it vanishes. Triangles already flipped (or flat) are
  // not held: they may unflip.
  auto cross = [](Complex a, Complex b) { return a.real() * b.imag() - a.imag() * b.real(); };
  double t_min = std::numeric_limits<double>::infinity();
  const size_t nt = tp_.corner_use.size() / 3;
  for (size_t t = 0; t < nt; ++t) {
    const Index a = tp_.corner_use[3 * t], b = tp_.corner_use[3 * t + 1], c = tp_.corner_use[3 * t + 2];
    const Complex p1 = z[b] - z[a], p2 = z[c] - z[a], q1 = dz[b] - dz[a], q2 = dz[c] - dz[a];
    const double A0 = cross(p1, p2), A1 = cross(p1, q2) + cross(q1, p2), A2 = cross(q1, q2);
    if (!(A0 > 0)) continue;
    double root = std::numeric_limits<double>::infinity();
    if (std::abs(A2) <= 1e-14 * (std::abs(A1) + A0)) {
      if (A1 < 0) root = -A0 / A1;
    } else {
      const double disc = A1 * A1 - 4 * A2 * A0;
      if (disc >= 0) {
        // Roots by the stable formula; the smallest positive one.
        const double qq = -0.5 * (A1 + std::copysign(std::sqrt(disc), A1));
        for (double r : {qq / A2, qq != 0 ? A0 / qq : std::numeric_limits<double>::infinity()})
          if (r > 0) root = std::min(root, r);
      }
    }
    t_min = std::min(t_min, root);
  }
  return t_min;
}

double GaussNewton::step(VectorXc& z, double s, double& energy_out) {
  double t0 = now();
  Eigen::VectorXd g;
  double e0 = 0;
  linearise(z, s, g, e0);
  // Without seams H_ is used as it is (a copy cost 170 MB at 1M triangles).
  SpMatR H_reduced;
  Eigen::VectorXd gy;
  if (identity_) {
    gy = g;
  } else {
    H_reduced = SpMatR(P_real_.transpose() * H_ * P_real_);
    gy = P_real_.transpose() * g;
  }
  const SpMatR& H = identity_ ? H_ : H_reduced;
  t_assembly_ += now() - t0;
  const Index nr = static_cast<Index>(H.rows());
  // Real constraint rows: Re and Im of each complex row over the reduced unknowns.
  const bool gauge = !gauge_row_.terms.empty();
  const bool whole = gauge && s < 1.0;  // hold the vector (size too), or only its direction
  const Index m = 2 * static_cast<Index>(rows_.size()) + (gauge ? (whole ? 2 : 1) : 0);
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(m, nr);
  auto add_complex_row = [&](Index r0, const LinearRow& row) {
    for (auto& [k, gk] : row.terms) {
      C(r0, 2 * k) += gk.real();
      C(r0, 2 * k + 1) += -gk.imag();
      C(r0 + 1, 2 * k) += gk.imag();
      C(r0 + 1, 2 * k + 1) += gk.real();
    }
  };
  for (size_t r = 0; r < rows_.size(); ++r) add_complex_row(2 * static_cast<Index>(r), rows_[r]);
  if (whole) {
    add_complex_row(m - 2, gauge_row_);
  } else if (gauge) {
    // Im(conj(v) sum g_k dy_k) = 0 with v the current vector: the step turns nothing.
    const VectorXc y = identity_ ? z : wefm::reduce(sub_, z);
    Complex v{0, 0};
    for (auto& [k, gk] : gauge_row_.terms) v += gk * y[k];
    const Complex cv = std::abs(v) > 0 ? std::conj(v) / std::abs(v) : Complex(1, 0);
    for (auto& [k, gk] : gauge_row_.terms) {
      const Complex cc = cv * gk;
      C(m - 1, 2 * k) += cc.imag();
      C(m - 1, 2 * k + 1) += cc.real();
    }
  }
  Eigen::VectorXd diag = H.diagonal();
  const double dmean = diag.mean() > 0 ? diag.mean() : 1.0;
  const std::vector<double> rho_before = compute_rho(tp_, c_, z);
  for (int attempt = 0; attempt < 8; ++attempt) {
    const Eigen::VectorXd shift = (lambda_ * diag).array() + 1e-12 * dmean;
    Eigen::VectorXd delta;
    if (!solve_step(H, shift, gy, C, delta)) {
      lambda_ *= 10;
      continue;
    }
    VectorXc dy(nr / 2);
    for (Index k = 0; k < nr / 2; ++k) dy[k] = Complex(delta[2 * k], delta[2 * k + 1]);
    const VectorXc dz = identity_ ? dy : VectorXc(sub_.P * dy);
    const double predicted = -gy.dot(delta);  // first-order decrease (negative)
    // Below s = 2 nothing in the energy keeps a triangle from passing through zero area, and a
    // step that flips triangles lands where Gauss-Newton does not find its way back (sphere with
    // a small hole at s = 1: the first full step flipped 194 triangles, 50 iterations later 8 were
    // still flipped). The step is cut short of the first triangle it would flip.
    const double t_max = std::min(1.0, 0.9 * first_flip(z, dz));
    for (double t = t_max; t >= t_max / 64; t *= 0.5) {
      const VectorXc zt = z + t * dz;
      const double et = energy(zt, s);
      if (std::isfinite(et) && et <= e0 + 1e-4 * t * predicted) {
        const std::vector<double> rho_after = compute_rho(tp_, c_, zt);
        double change = 0;
        for (size_t h = 0; h < rho_after.size(); ++h) change = std::max(change, std::abs(rho_after[h] / rho_before[h] - 1.0));
        z = zt;
        energy_out = et;
        lambda_ = t == 1.0 ? std::max(lambda_ * 0.1, 1e-10) : lambda_;
        return change;
      }
    }
    lambda_ *= 10;
  }
  energy_out = e0;
  return 0.0;  // no decrease possible: at a minimum to working precision
}

}  // namespace wefm
