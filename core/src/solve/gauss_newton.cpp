#include "wefm/core/solve/gauss_newton.hpp"
#include "wefm/core/sys/huge_pages.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <functional>
#include <limits>

#include "wefm/core/method/energy.hpp"
#include "wefm/core/sys/clock.hpp"
#include "wefm/core/sys/error.hpp"
#include "wefm/core/sys/parallel.hpp"

namespace wefm {

namespace {

void add_entry(Entry* es, int& ne, Index use, Complex l, Complex m) {
  for (int j = 0; j < ne; ++j)
    if (es[j].use == use) {
      es[j].l += l;
      es[j].m += m;
      return;
    }
  es[ne++] = {use, l, m};
}

// (L / |d|)^s without pow for the usual exponents: it is evaluated per half-edge in every pass, and
// pow is a measurable share of the continuation
// (docs/PERFORMANCE.md, "Measurements behind design choices").
inline double ratio_pow(double ratio, double s) {
  if (s == 1.0) return ratio;
  if (s == 2.0) return ratio * ratio;
  if (s == 0.0) return 1.0;
  return std::pow(ratio, s);
}

// The real vector (Re, Im interleaved) of a complex one, and back: same memory.
inline Eigen::Map<VectorXc> as_complex(Eigen::VectorXd& v) {
  return Eigen::Map<VectorXc>(reinterpret_cast<Complex*>(v.data()), v.size() / 2);
}
inline Eigen::Map<const VectorXc> as_complex(const Eigen::VectorXd& v) {
  return Eigen::Map<const VectorXc>(reinterpret_cast<const Complex*>(v.data()), v.size() / 2);
}

// One half-edge of the per-half-edge residual: its weighted prediction error r = p - q (p the
// part of degree 1 in z, q the altitude term of degree 1 - s) and its derivative l dz + m conj(dz)
// at the triangle's local corners j (base start), j1 (base end), j2 (opposite).
struct HalfEdgeRow {
  Complex p, q;
  Complex l[3], m[3];  // by local corner
  double len;          // |d|
};

inline void half_edge_row(const Coefficients& c, size_t h, double sw, const Complex zc[3], int j, double s, HalfEdgeRow& row) {
  const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
  const Complex d = zc[j1] - zc[j];
  const double len = std::sqrt(std::norm(d));
  const double ad = std::max(len, 1e-12);
  const Complex u = len > 0 ? d / len : Complex(1, 0);
  const double mag = c.beta[h] * ratio_pow(c.length[h] / ad, s);
  const double alpha = c.alpha[h];
  row.p = sw * (zc[j2] - zc[j] - alpha * d);
  row.q = sw * Complex(-mag * d.imag(), mag * d.real());  // sw i mag d
  const Complex lg(0, mag * (1.0 - 0.5 * s));
  const Complex mg = Complex(0, -mag * 0.5 * s) * u * u;
  row.l[j2] = sw;
  row.m[j2] = 0.0;
  row.l[j] = sw * (-(1.0 - alpha) + lg);
  row.m[j] = sw * mg;
  row.l[j1] = sw * (-alpha - lg);
  row.m[j1] = -sw * mg;
  row.len = len;
}

// Position of the diagonal entry of column i.
inline int diagonal_slot(const SpMatC& A, Index i) {
  const int* begin = A.innerIndexPtr() + A.outerIndexPtr()[i];
  const int* end = A.innerIndexPtr() + A.outerIndexPtr()[i + 1];
  const int* p = std::lower_bound(begin, end, static_cast<int>(i));
  if (p == end || *p != i) fail(Errc::internal, "Gauss-Newton matrix without a diagonal entry");
  return static_cast<int>(p - A.innerIndexPtr());
}

// Values of A on `pattern`, which holds A's pattern.
std::vector<Complex> values_on(const SpMatC& pattern, const SpMatC& A) {
  std::vector<Complex> out(static_cast<size_t>(pattern.nonZeros()), Complex(0, 0));
  for (Index col = 0; col < A.outerSize(); ++col) {
    const int* begin = pattern.innerIndexPtr() + pattern.outerIndexPtr()[col];
    const int* end = pattern.innerIndexPtr() + pattern.outerIndexPtr()[col + 1];
    for (SpMatC::InnerIterator it(A, col); it; ++it) {
      const int* p = std::lower_bound(begin, end, static_cast<int>(it.row()));
      if (p == end || *p != it.row()) fail(Errc::internal, "Gauss-Newton matrix outside its pattern");
      out[static_cast<size_t>(p - pattern.innerIndexPtr())] += it.value();
    }
  }
  return out;
}

// Column j of a real matrix (Re, Im interleaved) as a complex vector.
inline Eigen::Map<VectorXc> as_complex_col(Eigen::MatrixXd& m, Index j) {
  return Eigen::Map<VectorXc>(reinterpret_cast<Complex*>(m.col(j).data()), m.rows() / 2);
}

// conj(x) y
inline Complex cmul(Complex x, Complex y) {
  return Complex(x.real() * y.real() + x.imag() * y.imag(), x.real() * y.imag() - x.imag() * y.real());
}

std::atomic<bool> g_rotation_deflation{true};

}  // namespace

void set_rotation_deflation(bool on) { g_rotation_deflation.store(on); }
bool rotation_deflation() { return g_rotation_deflation.load(); }

GaussNewton::GaussNewton(const Topology& tp, const Coefficients& c, const SpMatC* B, double k, Residual form, SpMatC& K,
                         const SeamSubstitution& sub, std::vector<LinearRow> rows, Backend backend, double min_beta, int threads)
    : tp_(tp), c_(c), B_(B), form_(form), w_(compute_weights(tp, c, k, threads)), sub_(sub), barrier_(tp, c, min_beta), rows_(std::move(rows)),
      own_chol_(backend), threads_(threads) {
  const Index n = tp.use_count;
  K.makeCompressed();
  Kc_.swap(K);
  assign_huge(S_, static_cast<size_t>(Kc_.nonZeros()), Complex(0, 0));
  if (form == Residual::PerHalfEdge) {
    // Each row is weighted by sqrt(w) (per use, by w): keep only the one the form needs.
    for (double& w : w_) w = std::sqrt(w);
    sw_ = std::move(w_);
    w_ = {};
  }
  assign_huge(len_, c.alpha.size(), 0.0);
  if (form == Residual::PerHalfEdge) {
    // Where each triangle's 3x3 block lands, as offsets in its columns (a byte each, nine per
    // triangle): found once here instead of by binary searches in every linearisation.
    const size_t nt = tp.corner_use.size() / 3;
    assign_huge(block_offset_, 9 * nt);
    parallel_for(threads_, static_cast<Index>(nt), [&](Index t0, Index t1) {
      for (size_t t = static_cast<size_t>(t0); t < static_cast<size_t>(t1); ++t)
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b) {
            const Index ua = tp.corner_use[3 * t + static_cast<size_t>(a)], ub = tp.corner_use[3 * t + static_cast<size_t>(b)];
            const int o = slot(ua, ub) - Kc_.outerIndexPtr()[ub];
            block_offset_[9 * t + static_cast<size_t>(3 * a + b)] = static_cast<std::uint8_t>(o < kFarOffset ? o : kFarOffset);
          }
    });
  }
  if (B_ && B_->nonZeros()) {
    const SpMatC btb = boundary_gram(B_);
    for (Index col = 0; col < btb.outerSize(); ++col)
      for (SpMatC::InnerIterator it(btb, col); it; ++it) {
        btb_slot_.push_back(slot(static_cast<Index>(it.row()), col));
        btb_.push_back(it.value());
      }
  }
  if (form == Residual::PerUse) {
    // Rows per use: the half-edges opposite each use.
    opposite_.assign(static_cast<size_t>(n), {});
    for (size_t h = 0; h < c.alpha.size(); ++h)
      opposite_[static_cast<size_t>(tp.corner_use[static_cast<size_t>(HalfEdges::prev(static_cast<Index>(h)))])].push_back(h);
  }
  identity_ = sub.reduced == n;
  if (identity_)
    for (Index u = 0; u < n; ++u) identity_ = identity_ && sub.use_to_reduced[static_cast<size_t>(u)] == u;
}

int GaussNewton::slot(Index a, Index b) const {
  const int* begin = Kc_.innerIndexPtr() + Kc_.outerIndexPtr()[b];
  const int* end = Kc_.innerIndexPtr() + Kc_.outerIndexPtr()[b + 1];
  const int* p = std::lower_bound(begin, end, static_cast<int>(a));
  if (p == end || *p != a) fail(Errc::internal, "Gauss-Newton block outside the energy pattern");
  return static_cast<int>(p - Kc_.innerIndexPtr());
}

template <class F>
void GaussNewton::for_each_row(const VectorXc& z, double s, F&& f) const {
  for_each_row_split(z, s, [&](Complex p, Complex q, const Entry* es, int ne) { f(p - q, es, ne); });
}

template <class F>
void GaussNewton::for_each_row_split(const VectorXc& z, double s, F&& f) const {
  // The general form (both residuals): rows as lists of entries. The per-half-edge residual has
  // its own loops below, a triangle at a time.
  const size_t nh = c_.alpha.size();
  auto half_edge = [&](size_t h, double sw, Complex& p, Complex& q, Entry* es, int& ne) {
    const Index j = static_cast<Index>(h % 3);
    const size_t t3 = h - static_cast<size_t>(j);
    const Index u[3] = {tp_.corner_use[t3], tp_.corner_use[t3 + 1], tp_.corner_use[t3 + 2]};
    const Complex zc[3] = {z[u[0]], z[u[1]], z[u[2]]};
    HalfEdgeRow row;
    half_edge_row(c_, h, sw, zc, j, s, row);
    p += row.p;
    q += row.q;
    for (int a : {static_cast<int>((j + 2) % 3), static_cast<int>(j), static_cast<int>((j + 1) % 3)}) add_entry(es, ne, u[a], row.l[a], row.m[a]);
  };
  Entry es[64];
  if (form_ == Residual::PerHalfEdge) {
    for (size_t h = 0; h < nh; ++h) {
      Complex p{0, 0}, q{0, 0};
      int ne = 0;
      half_edge(h, sw_[h], p, q, es, ne);
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

void GaussNewton::linearise(const VectorXc& z, double s, VectorXc& g, double& energy) {
  const Index n = tp_.use_count;
  std::fill(Kc_.valuePtr(), Kc_.valuePtr() + Kc_.nonZeros(), Complex(0, 0));
  std::fill(S_.begin(), S_.end(), Complex(0, 0));
  g.setZero(n);
  energy = 0;
  if (form_ == Residual::PerUse) {
    linearise_per_use(z, s, g, energy);
  } else {
    // A triangle at a time: its three half-edges' rows all live on its three uses, so their
    // products are summed into one 3x3 block (Hermitian Kc, symmetric S) and scattered once.
    // The uses are cut into two halves, whatever the thread count: each half writes the entries of
    // its own columns and the gradient of its own uses, in triangle order (so every entry gets the
    // sums of the serial pass, in the same order), and a triangle with uses in both halves is
    // computed by both. The energy is summed per half (a triangle counts in the half of its first
    // use) and the halves added in order.
    Complex* kc = Kc_.valuePtr();
    Complex* sv = S_.data();
    const int* outer = Kc_.outerIndexPtr();
    const size_t nt = tp_.corner_use.size() / 3;
    double half_energy[kHalves] = {};
    parallel_for(threads_, kHalves, [&](Index part0, Index part1) {
      for (Index part = part0; part < part1; ++part) {
        const Index lo = static_cast<Index>(static_cast<std::int64_t>(n) * part / kHalves);
        const Index hi = static_cast<Index>(static_cast<std::int64_t>(n) * (part + 1) / kHalves);
        double e = 0;
        for (size_t t = 0; t < nt; ++t) {
          const Index u[3] = {tp_.corner_use[3 * t], tp_.corner_use[3 * t + 1], tp_.corner_use[3 * t + 2]};
          const bool mine[3] = {u[0] >= lo && u[0] < hi, u[1] >= lo && u[1] < hi, u[2] >= lo && u[2] < hi};
          if (!mine[0] && !mine[1] && !mine[2]) continue;
          const Complex zc[3] = {z[u[0]], z[u[1]], z[u[2]]};
          Complex kl[3][3] = {}, sl[3][3] = {}, gl[3] = {};
          double et = 0;
          for (int j = 0; j < 3; ++j) {
            const size_t h = 3 * t + static_cast<size_t>(j);
            HalfEdgeRow row;
            half_edge_row(c_, h, sw_[h], zc, j, s, row);
            if (mine[0]) len_[h] = row.len;
            const Complex r = row.p - row.q;
            et += std::norm(r);
            for (int a = 0; a < 3; ++a) {
              gl[a] += cmul(row.l[a], r) + row.m[a] * std::conj(r);
              for (int b = a; b < 3; ++b) {
                kl[a][b] += cmul(row.l[a], row.l[b]) + cmul(row.m[b], row.m[a]);
                sl[a][b] += cmul(row.l[a], row.m[b]) + cmul(row.l[b], row.m[a]);
              }
            }
          }
          // The shape barrier's row of this triangle (real r, entries (l, conj(l))), when active.
          double rb = 0;
          std::array<Complex, 3> lb;
          if (barrier_.row(t, zc[0], zc[1], zc[2], rb, lb)) {
            et += rb * rb;
            for (int a = 0; a < 3; ++a) {
              gl[a] += 2.0 * rb * std::conj(lb[static_cast<size_t>(a)]);
              for (int b = a; b < 3; ++b) {
                kl[a][b] += 2.0 * cmul(lb[static_cast<size_t>(a)], lb[static_cast<size_t>(b)]);
                sl[a][b] += 2.0 * std::conj(lb[static_cast<size_t>(a)] * lb[static_cast<size_t>(b)]);
              }
            }
          }
          if (mine[0]) e += et;
          const std::uint8_t* off = &block_offset_[9 * t];
          auto slot_of = [&](int a, int b) {
            const std::uint8_t o = off[3 * a + b];
            return o != kFarOffset ? outer[u[b]] + o : slot(u[a], u[b]);
          };
          for (int a = 0; a < 3; ++a) {
            if (mine[a]) g[u[a]] += gl[a];
            for (int b = a; b < 3; ++b) {
              if (mine[b]) {  // entry (u[a], u[b]) lives in column u[b]
                const int ab = slot_of(a, b);
                kc[ab] += kl[a][b];
                sv[ab] += sl[a][b];
              }
              if (b != a && mine[a]) {
                const int ba = slot_of(b, a);
                kc[ba] += std::conj(kl[a][b]);
                sv[ba] += sl[a][b];
              }
            }
          }
        }
        half_energy[part] = e;
      }
    }, 1);
    for (double e : half_energy) energy += e;
  }
  if (B_ && B_->nonZeros()) {
    // The boundary term is complex-linear: B^H B (constant) and B^H (B z).
    Complex* kc = Kc_.valuePtr();
    for (size_t i = 0; i < btb_slot_.size(); ++i) kc[btb_slot_[i]] += btb_[i];
    const VectorXc bz = (*B_) * z;
    energy += bz.squaredNorm();
    g += B_->adjoint() * bz;
  }
}

double GaussNewton::barrier_energy(const VectorXc& z) const {
  double e = 0, r = 0;
  std::array<Complex, 3> l;
  for (size_t t = 0; t < barrier_.triangles(); ++t)
    if (barrier_.row(t, z[tp_.corner_use[3 * t]], z[tp_.corner_use[3 * t + 1]], z[tp_.corner_use[3 * t + 2]], r, l)) e += r * r;
  return e;
}

void GaussNewton::linearise_barrier(const VectorXc& z, VectorXc& g, double& energy) {
  // A real residual r with dr = sum 2 Re(l_k dz_k): entries (l_k, conj(l_k)). Few triangles are
  // active (none on a well-shaped layout), so their blocks are found by search.
  Complex* kc = Kc_.valuePtr();
  Complex* sv = S_.data();
  double r = 0;
  std::array<Complex, 3> l;
  for (size_t t = 0; t < barrier_.triangles(); ++t) {
    const Index u[3] = {tp_.corner_use[3 * t], tp_.corner_use[3 * t + 1], tp_.corner_use[3 * t + 2]};
    if (!barrier_.row(t, z[u[0]], z[u[1]], z[u[2]], r, l)) continue;
    energy += r * r;
    for (int a = 0; a < 3; ++a) {
      const Complex la = l[static_cast<size_t>(a)], ma = std::conj(la);
      g[u[a]] += cmul(la, Complex(r, 0)) + ma * r;
      for (int b = 0; b < 3; ++b) {
        const Complex lb = l[static_cast<size_t>(b)], mb = std::conj(lb);
        const int ab = slot(u[a], u[b]);
        kc[ab] += cmul(la, lb) + cmul(mb, ma);
        sv[ab] += cmul(la, mb) + cmul(lb, ma);
      }
    }
  }
}

void GaussNewton::linearise_per_use(const VectorXc& z, double s, VectorXc& g, double& energy) {
  linearise_barrier(z, g, energy);
  // The eq. 7 rows sum several triangles' predictions: entries by use, blocks found one by one.
  Complex* kc = Kc_.valuePtr();
  Complex* sv = S_.data();
  for_each_row(z, s, [&](Complex r, const Entry* es, int ne) {
    energy += std::norm(r);
    for (int a = 0; a < ne; ++a) {
      g[es[a].use] += cmul(es[a].l, r) + es[a].m * std::conj(r);
      for (int b = 0; b < ne; ++b) {
        const int ab = slot(es[a].use, es[b].use);
        kc[ab] += cmul(es[a].l, es[b].l) + cmul(es[b].m, es[a].m);
        sv[ab] += cmul(es[a].l, es[b].m) + cmul(es[b].l, es[a].m);
      }
    }
  });
  for (size_t h = 0; h < len_.size(); ++h) {
    const Complex d = z[tp_.corner_use[static_cast<size_t>(HalfEdges::next(static_cast<Index>(h)))]] - z[tp_.corner_use[h]];
    len_[h] = std::sqrt(std::norm(d));
  }
}

double GaussNewton::energy_at(const VectorXc& z, double s, double* rho_change, ScaleSums* sums) const {
  // rho = L / |d| (1 where either is 0), against its value at the linearisation (len_).
  double change = 0;
  auto rho_change_of = [&](size_t h, double len) {
    const double L = c_.length[h];
    const double before = len_[h] > 0 && L > 0 ? L / len_[h] : 1.0;
    const double after = len > 0 && L > 0 ? L / len : 1.0;
    return std::abs(after / before - 1.0);
  };
  double e = 0;
  ScaleSums ps;
  if (form_ == Residual::PerUse) {
    for_each_row_split(z, s, [&](Complex p, Complex q, const Entry*, int) {
      e += std::norm(p - q);
      ps.P += std::norm(p);
      ps.Q += (std::conj(p) * q).real();
      ps.R += std::norm(q);
    });
    if (rho_change)
      for (size_t h = 0; h < len_.size(); ++h)
        change = std::max(change, rho_change_of(h, std::abs(z[tp_.corner_use[static_cast<size_t>(HalfEdges::next(static_cast<Index>(h)))]] -
                                                             z[tp_.corner_use[h]])));
  } else {
    // The rows' values only (no derivatives), in kBlocks fixed blocks of triangles whatever the
    // thread count, their sums added in block order.
    const size_t nt = tp_.corner_use.size() / 3;
    struct BlockSums {
      double e = 0, change = 0;
      ScaleSums ps;
    };
    BlockSums blocks[kBlocks];
    parallel_for(threads_, kBlocks, [&](Index b0, Index b1) {
      for (Index blk = b0; blk < b1; ++blk) {
        BlockSums& bs = blocks[blk];
        const size_t t0 = nt * static_cast<size_t>(blk) / kBlocks, t1 = nt * static_cast<size_t>(blk + 1) / kBlocks;
        for (size_t t = t0; t < t1; ++t) {
          const Complex zc[3] = {z[tp_.corner_use[3 * t]], z[tp_.corner_use[3 * t + 1]], z[tp_.corner_use[3 * t + 2]]};
          for (int j = 0; j < 3; ++j) {
            const size_t h = 3 * t + static_cast<size_t>(j);
            const Complex d = zc[(j + 1) % 3] - zc[j];
            const double len = std::sqrt(std::norm(d));
            const double mag = c_.beta[h] * ratio_pow(c_.length[h] / std::max(len, 1e-12), s);
            const Complex r = sw_[h] * (zc[(j + 2) % 3] - zc[j] - c_.alpha[h] * d - Complex(-mag * d.imag(), mag * d.real()));
            bs.e += std::norm(r);
            if (rho_change) bs.change = std::max(bs.change, rho_change_of(h, len));
            if (sums) {
              const Complex p = sw_[h] * (zc[(j + 2) % 3] - zc[j] - c_.alpha[h] * d);
              const Complex q = sw_[h] * Complex(-mag * d.imag(), mag * d.real());
              bs.ps.P += std::norm(p);
              bs.ps.Q += p.real() * q.real() + p.imag() * q.imag();
              bs.ps.R += std::norm(q);
            }
          }
          double rb = 0;
          std::array<Complex, 3> lb;
          if (barrier_.row(t, zc[0], zc[1], zc[2], rb, lb)) bs.ps.barrier += rb * rb;
        }
      }
    }, 1);
    for (const BlockSums& bs : blocks) {
      e += bs.e;
      change = std::max(change, bs.change);
      ps.P += bs.ps.P;
      ps.Q += bs.ps.Q;
      ps.R += bs.ps.R;
      ps.barrier += bs.ps.barrier;
    }
  }
  if (B_ && B_->nonZeros()) {
    const double eb = ((*B_) * z).squaredNorm();
    e += eb;
    ps.P += eb;
  }
  if (form_ == Residual::PerUse) ps.barrier = barrier_energy(z);
  e += ps.barrier;
  if (rho_change) *rho_change = change;
  if (sums) *sums = ps;
  return e;
}

double GaussNewton::energy(const VectorXc& z, double s) const { return energy_at(z, s, nullptr, nullptr); }

double GaussNewton::rescale(VectorXc& z, double s, double& energy_after) {
  // E(a) = a^2 P - 2 a^(2-s) Q + a^(2-2s) R; dE/da = 0 <=> P t^2 - (2-s) Q t + (1-s) R = 0, t = a^s.
  // The sums at z come from the line search that accepted z, when it did (one pass fewer).
  double P = 0, Q = 0, R = 0, Eb = 0;  // Eb: the shape barrier, unchanged by a scaling
  const bool known = accepted_sums_valid_;
  if (known) {
    P = accepted_sums_.P;
    Q = accepted_sums_.Q;
    R = accepted_sums_.R;
    Eb = accepted_sums_.barrier;
    accepted_sums_valid_ = false;
  } else {
    ScaleSums ps;
    energy_at(z, s, nullptr, &ps);
    P = ps.P;
    Q = ps.Q;
    R = ps.R;
    Eb = ps.barrier;
  }
  energy_after = P - 2 * Q + R + Eb;
  if (!(P > 0) || s <= 0) return 1.0;
  const double b = -(2 - s) * Q, c = (1 - s) * R, disc = b * b - 4 * P * c;
  if (disc < 0) return 1.0;
  const double t = (-b + std::sqrt(disc)) / (2 * P);  // the larger root: the local minimum
  const double a = t > 0 ? std::pow(t, 1.0 / s) : 1.0;
  if (!std::isfinite(a) || !(a > 0)) return 1.0;
  z = ((z.array() - center_) * a + center_).matrix();
  energy_after = a * a * P - 2 * std::pow(a, 2 - s) * Q + std::pow(a, 2 - 2 * s) * R + Eb;
  return a;
}

// Refactorises the preconditioner: the complex-linear part Kc plus the mean of each unknown's two
// real shifts, in the shared factor's K_PP (with its Schur complement on the split pair) or in the
// own factor.
void GaussNewton::refactor(const SpMatC& Kc, const Eigen::VectorXd& shift) {
  const Index n = static_cast<Index>(Kc.rows());
  auto shift_of = [&](Index i) { return 0.5 * (shift[2 * i] + shift[2 * i + 1]); };
  if (!p_of_.empty()) {
    std::fill(Kpp_.valuePtr(), Kpp_.valuePtr() + Kpp_.nonZeros(), Complex(0, 0));
    for (Index v = 0; v < Kc_.nonZeros(); ++v)
      if (kc_to_pp_[static_cast<size_t>(v)] >= 0) Kpp_.valuePtr()[kc_to_pp_[static_cast<size_t>(v)]] = Kc_.valuePtr()[v];
    for (Index u = 0; u < n; ++u) {
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
    SpMatC Kd = Kc;
    for (Index i = 0; i < n; ++i) Kd.coeffRef(i, i) += shift_of(i);
    chol_->factorize(Kd);
  }
  // From here on the factor only preconditions: in single precision it halves the bytes each
  // application reads (they are memory-bound; the CG stays in double). Wx_ and Sx_ are taken in
  // double first: Sx_ is a difference of nearly equal terms (K is singular along translations),
  // and with the exact Wx_ the preconditioner stays Hermitian positive definite whatever the
  // float solve's rounding (it is [I -W; 0 I] diag(M_PP^-1, Sx^-1) [I 0; -W^H I]).
  chol_->keep_single_precision();
  factored_ = true;
  ++refactorisations_;
  units_valid_ = false;
}

// Projected conjugate gradients on (H + diag(shift)) delta = -g with C delta = 0, preconditioned
// by a complex factorisation of the complex-linear part of an earlier Gauss-Newton matrix (the
// constraint preconditioner keeps every iterate in the null space of C). The real 2n matrix
// itself is not factorised: its factor would more than double the solve's peak memory, while the
// complex one reuses the s = 0 factor's storage, refactorised in place, at the price of a few more
// CG iterations per step (docs/PERFORMANCE.md, "Measurements behind design choices").
class GaussNewton::ProjectedCg {
 public:
  ProjectedCg(GaussNewton& gn, const SpMatC& Kc, const Complex* S, const Eigen::VectorXd& shift, const Eigen::MatrixXd& C,
              const Eigen::VectorXd& rotation)
      : gn_(gn), Kc_(Kc), S_(S), shift_(shift), C_(C), rotation_(rotation), nr_(2 * static_cast<Index>(Kc.rows())) {
    // The unknowns the constraint rows touch (the gauge's two uses, usually), and their real
    // columns that are not zero: C y reads only those.
    for (Index k = 0; k < nr_ / 2; ++k)
      for (Index j = 0; j < C.rows(); ++j)
        if (C(j, 2 * k) != 0.0 || C(j, 2 * k + 1) != 0.0) {
          touched_.push_back(k);
          break;
        }
    for (Index k : touched_)
      for (Index col : {2 * k, 2 * k + 1})
        if ((C.col(col).array() != 0.0).any()) c_cols_.push_back(col);
  }

  void project();
  void deflation();
  // CG from delta = 0; false when it made no progress with a fresh factor.
  bool solve(const Eigen::VectorXd& g, Eigen::VectorXd& delta, bool fresh);

 private:
  void apply(const Eigen::VectorXd& p, Eigen::VectorXd& q) const;
  double dot(const Eigen::VectorXd& x, const Eigen::VectorXd& y) const;
  void elementwise(const std::function<void(Index, Index)>& body) const { parallel_for(gn_.threads_, nr_, body); }
  void precondition(const Eigen::VectorXd& rr, Eigen::VectorXd& y);

  GaussNewton& gn_;
  const SpMatC& Kc_;
  const Complex* S_;
  const Eigen::VectorXd& shift_;
  const Eigen::MatrixXd& C_;
  const Eigen::VectorXd& rotation_;
  const Index nr_;
  std::vector<Index> touched_, c_cols_;
  Eigen::MatrixXd W_;  // M^{-1} C^T
  Eigen::FullPivLU<Eigen::MatrixXd> Sc_;  // C W
  Eigen::MatrixXd zr_m_;
  Eigen::VectorXd dv_;  // the rotation, projected: the coarse correction's direction
  double de_ = 0;       // its curvature dv^T A dv
  bool deflate_ = false;
};

// W = M^{-1} C^T and the factorised C W, for the current factor.
void GaussNewton::ProjectedCg::project() {
  const Eigen::MatrixXd& C = C_;
  if (C.rows() == 0) return;
  if (touched_.size() > kMaxCachedUnits) {
    gn_.precondition(C.transpose(), W_);
  } else {
    // W = M^{-1} C^T from M^{-1} e_k, kept while the factor is: the preconditioner is
    // complex-linear, so a row's column is a complex combination of those (a solve per step
    // saved; the rows' direction changes with the layout, their unknowns do not).
    if (touched_ != gn_.unit_uses_) {
      gn_.unit_uses_ = touched_;
      gn_.units_valid_ = false;
    }
    if (!gn_.units_valid_) {
      Eigen::MatrixXd E = Eigen::MatrixXd::Zero(nr_, static_cast<Index>(touched_.size()));
      for (size_t q = 0; q < touched_.size(); ++q) E(2 * touched_[q], static_cast<Index>(q)) = 1.0;
      gn_.precondition(E, gn_.units_);
      gn_.units_valid_ = true;
    }
    W_.setZero(nr_, C.rows());
    for (Index j = 0; j < C.rows(); ++j)
      for (size_t q = 0; q < touched_.size(); ++q) {
        const Index k = touched_[q];
        const Complex c(C(j, 2 * k), C(j, 2 * k + 1));
        if (c == Complex(0, 0)) continue;
        as_complex_col(W_, j) += c * as_complex_col(gn_.units_, static_cast<Index>(q));
      }
  }
  Sc_.compute(C * W_);
}

// q = (H + diag(shift)) p, H p = Kc p + S conj(p) in complex form. Row i of Kc is the conjugate
// of its column i (Hermitian) and row i of S its column i (symmetric): each q_i is gathered from
// one column, so the rows split over threads with the same sums whatever their number.
void GaussNewton::ProjectedCg::apply(const Eigen::VectorXd& p, Eigen::VectorXd& q) const {
  const int* outer = Kc_.outerIndexPtr();
  const int* inner = Kc_.innerIndexPtr();
  const Complex* kv = Kc_.valuePtr();
  const Complex* S = S_;
  const Eigen::VectorXd& shift = shift_;
  const Eigen::Map<const VectorXc> pc = as_complex(p);
  Eigen::Map<VectorXc> qc = as_complex(q);
  parallel_for(gn_.threads_, static_cast<Index>(pc.size()), [&](Index i0, Index i1) {
    for (Index i = i0; i < i1; ++i) {
      Complex acc(0, 0);
      for (int v = outer[i]; v < outer[i + 1]; ++v) {
        const Complex x = pc[inner[v]];
        acc += cmul(kv[v], x) + S[v] * std::conj(x);
      }
      qc[i] = acc + Complex(shift[2 * i] * pc[i].real(), shift[2 * i + 1] * pc[i].imag());
    }
  });
}

// CG's vector passes (each reads one or two vectors of the problem's size; together they cost about
// as much as a float solve) split over threads: element-wise updates, and dot products summed over
// kBlocks fixed blocks in block order, so the same bits for any thread count.
double GaussNewton::ProjectedCg::dot(const Eigen::VectorXd& x, const Eigen::VectorXd& y) const {
  const Index nr = nr_;
  double part[kBlocks] = {};
  parallel_for(gn_.threads_, kBlocks, [&](Index b0, Index b1) {
    for (Index blk = b0; blk < b1; ++blk) {
      const Index i0 = nr * blk / kBlocks, i1 = nr * (blk + 1) / kBlocks;
      part[blk] = x.segment(i0, i1 - i0).dot(y.segment(i0, i1 - i0));
    }
  }, 1);
  double sum = 0;
  for (double v : part) sum += v;
  return sum;
}

// The energy does not change when the layout turns, and the step matrix is the Gauss-Newton one:
// along the rotation v its curvature is the energy (the residuals turn with the layout), a
// thousandth of the complex-linear part's (1M plate, s = 1: v^T A v / v^T M v = 0.001). The gauge
// row only holds the direction between two uses, so rotations bent near them stay in the step's
// space with a small Rayleigh quotient (CG's Ritz values reach 0.04 on the plate against 0.15 on
// the disk), and CG spends iterations on them. The preconditioner gets a coarse correction along
// v, projected into the constraint rows' null space: B = M^-1 + v v^T / (v^T A v), symmetric
// positive definite when M is, which lifts that mode's eigenvalue to about 1. It costs one
// operator product per step and a dot product and an update per application; with C v = 0 the
// projection's W = B C^T = M^-1 C^T is unchanged. The balancing form (Q + (I - QA) M^-1 (I - AQ))
// took a few fewer CG iterations for one more preconditioner solve per step: measured in
// docs/PERFORMANCE.md.
void GaussNewton::ProjectedCg::deflation() {
  deflate_ = false;
  if (rotation_.size() != nr_) return;
  dv_ = rotation_;
  if (C_.rows() > 0) {
    Eigen::VectorXd cv = Eigen::VectorXd::Zero(C_.rows());
    for (Index k : c_cols_) cv += C_.col(k) * dv_[k];
    dv_ -= W_ * Sc_.solve(cv);
  }
  Eigen::VectorXd av(nr_);
  apply(dv_, av);
  de_ = dot(dv_, av);
  deflate_ = de_ > 0 && std::isfinite(de_);
}

// y = the projected, deflated preconditioner applied to rr.
void GaussNewton::ProjectedCg::precondition(const Eigen::VectorXd& rr, Eigen::VectorXd& y) {
  gn_.precondition(rr, zr_m_);
  if (deflate_) {
    const double a = dot(dv_, rr) / de_;
    elementwise([&](Index i0, Index i1) {
      for (Index i = i0; i < i1; ++i) zr_m_(i, 0) += a * dv_[i];
    });
  }
  y.resize(nr_);
  if (C_.rows() == 0) {
    elementwise([&](Index i0, Index i1) { y.segment(i0, i1 - i0) = zr_m_.col(0).segment(i0, i1 - i0); });
    return;
  }
  Eigen::VectorXd cy = Eigen::VectorXd::Zero(C_.rows());
  for (Index k : c_cols_) cy += C_.col(k) * zr_m_(k, 0);
  const Eigen::VectorXd t = Sc_.solve(cy);
  elementwise([&](Index i0, Index i1) {
    for (Index i = i0; i < i1; ++i) y[i] = zr_m_(i, 0) - W_.row(i).dot(t);
  });
}

// CG in phases: one per factor. A stale factor gets as many iterations as the last fresh one
// needed plus kRefactorExtra, then it is refactorised (what the extra iterations would cost) and
// CG goes on from delta.
bool GaussNewton::ProjectedCg::solve(const Eigen::VectorXd& g, Eigen::VectorXd& delta, bool fresh) {
  const Index nr = nr_;
  Eigen::VectorXd r(nr), zr(nr), p(nr), q(nr);
  double rz_stale = 0;
  delta.setZero(nr);
  r = -g;
  gn_.last_pcg_ = 0;
  double target = 0;  // on r.z, relative to its start: kCgTolerance
  for (int phase = 0;; ++phase) {
    precondition(r, zr);
    p = zr;
    double rz = dot(r, zr);
    if (phase == 0 || !(rz_stale > 0)) {
      target = kCgTolerance * rz;
    } else {
      // A refactorisation mid-step: go on from delta (every iterate keeps C delta = 0) with the
      // reduction still missing carried over to the new preconditioner's norm.
      target *= rz / rz_stale;
    }
    bool converged = rz <= target;
    const bool baseline = phase == 0 && fresh;  // this count is the fresh factor's
    const int limit = baseline ? kMaxCgIterations : std::min(kMaxCgIterations, gn_.fresh_pcg_ + kRefactorExtra);
    int its = 0;
    for (; its < limit && !converged; ++its) {
      apply(p, q);
      const double pq = dot(p, q);
      if (!(pq > 0)) break;
      const double a = rz / pq;
      elementwise([&](Index i0, Index i1) {
        for (Index i = i0; i < i1; ++i) {
          delta[i] += a * p[i];
          r[i] -= a * q[i];
        }
      });
      precondition(r, zr);
      const double rz_new = dot(r, zr);
      ++gn_.pcg_iterations_;
      ++gn_.last_pcg_;
      converged = !(rz_new > target);
      const double beta = rz_new / rz;
      elementwise([&](Index i0, Index i1) {
        for (Index i = i0; i < i1; ++i) p[i] = zr[i] + beta * p[i];
      });
      rz = rz_new;
    }
    rz_stale = rz;
    if (!delta.allFinite()) {  // start again from zero
      delta.setZero(nr);
      r = -g;
      rz_stale = 0;
    }
    if (baseline) {
      gn_.fresh_pcg_ = its;
      gn_.baseline_pending_ = false;
    }
    if (converged) return true;
    // Every CG iterate lowers the quadratic model, so an unfinished one is still a descent
    // direction (the line search sizes it); a stale factor is refactorised first.
    if (fresh) return delta.squaredNorm() > 0;
    gn_.refactor(Kc_, shift_);
    fresh = true;
    gn_.baseline_pending_ = true;  // the next step measures the new factor
    project();
    deflation();
  }
}

bool GaussNewton::solve_step(const SpMatC& Kc, const Complex* S, const Eigen::VectorXd& shift, const Eigen::VectorXd& g,
                             const Eigen::MatrixXd& C, const Eigen::VectorXd& rotation, Eigen::VectorXd& delta) {
  // Refactorise when the factor has gone stale (kRefactorExtra). A count, not a timing: results
  // must not depend on machine load.
  bool fresh = baseline_pending_;  // refactorised at the end of the last step: as good as fresh
  if (!factored_ || (!fresh && last_pcg_ > fresh_pcg_ + kRefactorExtra)) {
    refactor(Kc, shift);
    fresh = true;
  }
  ProjectedCg cg(*this, Kc, S, shift, C, rotation);
  cg.project();
  cg.deflation();
  return cg.solve(g, delta, fresh);
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
  // K_PP's pattern as PartitionedKKT::set_matrix built it: K's columns and rows without x0, x1,
  // renumbered (the numbering keeps the order, so every column stays sorted). Written in place:
  // triplets and their sort would add more than a copy of the pattern at the peak of the solve.
  const int* outer = Kc_.outerIndexPtr();
  const int* inner = Kc_.innerIndexPtr();
  Index nnz = 0;
  for (Index c = 0; c < n; ++c)
    if (p_of_[static_cast<size_t>(c)] >= 0)
      for (int v = outer[c]; v < outer[c + 1]; ++v) nnz += p_of_[static_cast<size_t>(inner[v])] >= 0;
  Kpp_.resize(n - 2, n - 2);
  Kpp_.resizeNonZeros(nnz);
  int* pp_outer = Kpp_.outerIndexPtr();
  int* pp_inner = Kpp_.innerIndexPtr();
  kc_to_pp_.assign(static_cast<size_t>(Kc_.nonZeros()), -1);
  px_entries_.clear();
  Index pos = 0;
  pp_outer[0] = 0;
  for (Index c = 0; c < n; ++c) {
    const Index pc = p_of_[static_cast<size_t>(c)];
    for (int v = outer[c]; v < outer[c + 1]; ++v) {
      const Index pr = p_of_[static_cast<size_t>(inner[v])];
      if (pc < 0 && pr >= 0) px_entries_.push_back({v, pr, static_cast<Index>(c == x0 ? 0 : 1)});
      if (pr < 0 || pc < 0) continue;
      pp_inner[pos] = pr;
      kc_to_pp_[static_cast<size_t>(v)] = pos++;
    }
    if (pc >= 0) pp_outer[pc + 1] = pos;
  }
  std::fill(Kpp_.valuePtr(), Kpp_.valuePtr() + nnz, Complex(1, 0));
  return true;
}

void GaussNewton::precondition(const Eigen::MatrixXd& r, Eigen::MatrixXd& out) {
  // The gathers and scatters around the factor's solve are element by element: split over threads
  // they give the same bits (each is a pass over one or two vectors, a fair share of a float solve).
  const Index n = r.rows() / 2;
  auto at = [&](Index k, Index j) { return Complex(r(2 * k, j), r(2 * k + 1, j)); };
  out.resize(r.rows(), r.cols());
  auto put = [&](Index k, Index j, Complex v) {
    out(2 * k, j) = v.real();
    out(2 * k + 1, j) = v.imag();
  };
  if (!p_of_.empty()) {
    pre_b_.resize(n - 2, r.cols());
    parallel_for(threads_, n, [&](Index k0, Index k1) {
      for (Index j = 0; j < r.cols(); ++j)
        for (Index k = k0; k < k1; ++k)
          if (p_of_[static_cast<size_t>(k)] >= 0) pre_b_(p_of_[static_cast<size_t>(k)], j) = at(k, j);
    });
    // [K_PP K_PX; K_XP K_XX] x = b by block elimination: y = K_PP^{-1} b_P,
    // x_X = S^{-1} (b_X - K_PX^H y), x_P = y - W x_X.
    pre_x_ = chol_->solve(pre_b_);
    Eigen::MatrixXcd bx(2, r.cols());
    for (Index j = 0; j < r.cols(); ++j)
      for (int s = 0; s < 2; ++s) bx(s, j) = at(split_[s], j);
    // K_PX^H y = W^H K_PP y = W^H b_P (K_PP Hermitian): no product with K_PX needed.
    const Eigen::MatrixXcd xx = Sx_.fullPivLu().solve(bx - Wx_.adjoint() * pre_b_);
    parallel_for(threads_, n, [&](Index k0, Index k1) {
      for (Index j = 0; j < r.cols(); ++j)
        for (Index k = k0; k < k1; ++k) {
          const Index pk = p_of_[static_cast<size_t>(k)];
          if (pk >= 0) put(k, j, pre_x_(pk, j) - (Wx_(pk, 0) * xx(0, j) + Wx_(pk, 1) * xx(1, j)));
        }
    });
    for (Index j = 0; j < r.cols(); ++j)
      for (int s = 0; s < 2; ++s) put(split_[s], j, xx(s, j));
  } else {
    pre_b_.resize(n, r.cols());
    parallel_for(threads_, n, [&](Index k0, Index k1) {
      for (Index j = 0; j < r.cols(); ++j)
        for (Index k = k0; k < k1; ++k) pre_b_(k, j) = at(k, j);
    });
    pre_x_ = chol_->solve(pre_b_);
    parallel_for(threads_, n, [&](Index k0, Index k1) {
      for (Index j = 0; j < r.cols(); ++j)
        for (Index k = k0; k < k1; ++k) put(k, j, pre_x_(k, j));
    });
  }
}

double GaussNewton::first_flip(const VectorXc& z, const VectorXc& dz) const {
  // Twice the signed area of a triangle along z + t dz is A0 + A1 t + A2 t^2; for each triangle
  // positive now, the smallest t > 0 where it vanishes. Triangles already flipped (or flat) are
  // not held: they may unflip.
  auto cross = [](Complex a, Complex b) { return a.real() * b.imag() - a.imag() * b.real(); };
  // A minimum: the same whatever the blocks' order.
  const size_t nt = tp_.corner_use.size() / 3;
  double block_min[kBlocks];
  std::fill(block_min, block_min + kBlocks, std::numeric_limits<double>::infinity());
  parallel_for(threads_, kBlocks, [&](Index b0, Index b1) {
    for (Index blk = b0; blk < b1; ++blk) {
      double& t_min = block_min[blk];
      for (size_t t = nt * static_cast<size_t>(blk) / kBlocks; t < nt * static_cast<size_t>(blk + 1) / kBlocks; ++t) {
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
    }
  }, 1);
  const double t_min = *std::min_element(block_min, block_min + kBlocks);
  return t_min;
}

// The step's constraint rows in real form: Re and Im of each complex row over the reduced
// unknowns, then the gauge row: whole below s = 1 (it holds the vector, size too), else only its
// direction.
Eigen::MatrixXd GaussNewton::step_constraints(const VectorXc& z, double s, Index nr) const {
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
  return C;
}

// The layout's infinitesimal rotation i (z - mean) over the step's unknowns, which the step's CG
// deflates (solve_step); empty when rotation_deflation() is off.
Eigen::VectorXd GaussNewton::step_rotation(const VectorXc& z, Index nr) const {
  Eigen::VectorXd rotation;
  if (rotation_deflation()) {
    const Complex mean = z.mean();
    const VectorXc turn = Complex(0, 1) * (z.array() - mean).matrix();
    rotation.resize(nr);
    as_complex(rotation) = identity_ ? turn : wefm::reduce(sub_, turn);
  }
  return rotation;
}

double GaussNewton::step(VectorXc& z, double s, double& energy_out) {
  accepted_sums_valid_ = false;
  double t0 = now();
  VectorXc g;
  double e0 = 0;
  linearise(z, s, g, e0);
  last_e0_ = e0;
  // Without seams Kc_ and S_ are used as they are; with seams the reduced parts are
  // Kr = P^H Kc P and Sr = P^H S conj(P) (dz = P dy: H dz = Kc P dy + S conj(P) conj(dy)).
  SpMatC Kr;
  std::vector<Complex> Sr_values;
  Eigen::VectorXd gy(2 * (identity_ ? tp_.use_count : sub_.reduced));
  if (identity_) {
    as_complex(gy) = g;
  } else {
    SpMatC Sfull = Kc_;
    std::copy(S_.begin(), S_.end(), Sfull.valuePtr());
    const SpMatC Kp = SpMatC(sub_.P.adjoint() * Kc_ * sub_.P);
    const SpMatC Sp = SpMatC(sub_.P.adjoint() * Sfull * SpMatC(sub_.P.conjugate()));
    // Both on one pattern (their union; the same structure in exact arithmetic).
    Kr = Kp + Sp;
    Kr.makeCompressed();
    Sr_values = values_on(Kr, Sp);
    const std::vector<Complex> kv = values_on(Kr, Kp);
    std::copy(kv.begin(), kv.end(), Kr.valuePtr());
    as_complex(gy) = sub_.P.adjoint() * g;
  }
  const SpMatC& Kc = identity_ ? Kc_ : Kr;
  const Complex* S = identity_ ? S_.data() : Sr_values.data();
  t_assembly_ += now() - t0;
  const Index nr = 2 * static_cast<Index>(Kc.rows());
  const Eigen::MatrixXd C = step_constraints(z, s, nr);
  // The real matrix's diagonal: Kc_ii +- Re S_ii (S_ii conj acts as diag(Re, -Re) on (Re, Im)).
  Eigen::VectorXd diag(nr);
  for (Index i = 0; i < nr / 2; ++i) {
    const int v = diagonal_slot(Kc, i);
    diag[2 * i] = Kc.valuePtr()[v].real() + S[v].real();
    diag[2 * i + 1] = Kc.valuePtr()[v].real() - S[v].real();
  }
  const Eigen::VectorXd rotation = step_rotation(z, nr);
  const double dmean = diag.mean() > 0 ? diag.mean() : 1.0;
  for (int attempt = 0; attempt < 8; ++attempt) {
    const Eigen::VectorXd shift = (lambda_ * diag).array() + 1e-12 * dmean;
    Eigen::VectorXd delta;
    if (!solve_step(Kc, S, shift, gy, C, rotation, delta)) {
      lambda_ *= 10;
      continue;
    }
    const VectorXc dy = as_complex(static_cast<const Eigen::VectorXd&>(delta));
    const VectorXc dz = identity_ ? dy : VectorXc(sub_.P * dy);
    const double predicted = -gy.dot(delta);  // first-order decrease (negative)
    // Below s = 2 nothing in the energy keeps a triangle from passing through zero area, and a
    // step that flips triangles lands where Gauss-Newton does not find its way back (sphere with
    // a small hole at s = 1: the first full step flipped 194 triangles, 50 iterations later 8 were
    // still flipped). The step is cut short of the first triangle it would flip.
    const double t_max = std::min(1.0, 0.9 * first_flip(z, dz));
    for (double t = t_max; t >= t_max / 64; t *= 0.5) {
      const VectorXc zt = z + t * dz;
      double change = 0;
      ScaleSums sums;
      const double et = energy_at(zt, s, &change, &sums);
      if (std::isfinite(et) && et <= e0 + 1e-4 * t * predicted) {
        z = zt;
        accepted_sums_ = sums;
        accepted_sums_valid_ = true;
        energy_out = et;
        last_full_ = attempt == 0 && t == 1.0;  // a step after raising the damping is not a full one either
        lambda_ = t == 1.0 ? std::max(lambda_ * 0.1, 1e-10) : lambda_;
        return change;
      }
    }
    lambda_ *= 10;
  }
  energy_out = e0;
  last_full_ = false;
  return 0.0;  // no decrease possible: at a minimum to working precision
}

}  // namespace wefm
