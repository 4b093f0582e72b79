#include "wefm/core/meshing/predicates.hpp"

#include <cmath>
#include <limits>

namespace wefm::meshing {
namespace {

// Exact arithmetic on expansions: sums of non-overlapping doubles in increasing magnitude, built
// from error-free transformations. fma gives the exact product error in one step. Expansions live in
// fixed buffers on the stack: the filters fail on every nearly collinear boundary (a straight model
// edge's nodes), so the exact path is a common one and must not allocate.

inline void two_sum(double a, double b, double& s, double& e) {
  s = a + b;
  const double bv = s - a, av = s - bv;
  e = (a - av) + (b - bv);
}

// h[0..n) += b in place; returns the new length, at most n + 1 (h must hold it). Each output term
// is written at or before the input term just read, so the input is never overwritten unread.
int grow(double* h, int n, double b) {
  double q = b;
  int k = 0;
  for (int i = 0; i < n; ++i) {
    double s, e;
    two_sum(q, h[i], s, e);
    if (e != 0) h[k++] = e;
    q = s;
  }
  h[k++] = q;
  return k;
}

// x[0..nx) * b into out (room for 2 nx terms); returns its length.
int scale(const double* x, int nx, double b, double* out) {
  int n = 0;
  for (int i = 0; i < nx; ++i) {
    const double p = x[i] * b;
    n = grow(out, n, std::fma(x[i], b, -p));
    n = grow(out, n, p);
  }
  return n;
}

// An expansion of at most N terms.
template <int N>
struct Expansion {
  double v[N];
  int n = 0;
};

// The exact difference a - b (two terms).
Expansion<2> diff(double a, double b) {
  Expansion<2> out;
  two_sum(a, -b, out.v[1], out.v[0]);
  out.n = 2;
  return out;
}

constexpr int kProductTerms(int nx, int ny) { return 2 * nx * ny; }

// acc += sign x y. acc grows by at most one term per term of each scaled copy of x: 2 |x| |y| in
// all (its capacity N must allow for that on top of its length).
template <int N, int NX, int NY>
void add_product(Expansion<N>& acc, const Expansion<NX>& x, const Expansion<NY>& y, double sign) {
  double scaled[2 * NX];
  for (int j = 0; j < y.n; ++j) {
    const int m = scale(x.v, x.n, sign * y.v[j], scaled);
    for (int k = 0; k < m; ++k) acc.n = grow(acc.v, acc.n, scaled[k]);
  }
}

template <int N>
double sign_of(const Expansion<N>& x) {
  for (int i = x.n - 1; i >= 0; --i)
    if (x.v[i] != 0) return x.v[i] > 0 ? 1.0 : -1.0;
  return 0.0;
}

constexpr double kEps = std::numeric_limits<double>::epsilon() * 0.5;
// Error bound coefficient chosen generously above Shewchuk's (10+96e)e (orient2d's is in the header).
constexpr double kIncircleBound = 12.0 * kEps;

// x0 y0 + sign x1 y1 of two-term differences: at most 2 * 8 terms.
using Cross = Expansion<2 * kProductTerms(2, 2)>;
Cross two_products(const Expansion<2>& x0, const Expansion<2>& y0, const Expansion<2>& x1, const Expansion<2>& y1, double sign) {
  Cross out;
  add_product(out, x0, y0, 1.0);
  add_product(out, x1, y1, sign);
  return out;
}

double orient_exact(const P2& a, const P2& b, const P2& c) {
  return sign_of(two_products(diff(a.x(), c.x()), diff(b.y(), c.y()), diff(a.y(), c.y()), diff(b.x(), c.x()), -1.0));
}

double incircle_exact(const P2& a, const P2& b, const P2& c, const P2& d) {
  const Expansion<2> adx = diff(a.x(), d.x()), ady = diff(a.y(), d.y());
  const Expansion<2> bdx = diff(b.x(), d.x()), bdy = diff(b.y(), d.y());
  const Expansion<2> cdx = diff(c.x(), d.x()), cdy = diff(c.y(), d.y());
  const Cross alift = two_products(adx, adx, ady, ady, 1.0), blift = two_products(bdx, bdx, bdy, bdy, 1.0),
              clift = two_products(cdx, cdx, cdy, cdy, 1.0);
  const Cross bc = two_products(bdx, cdy, bdy, cdx, -1.0), ca = two_products(cdx, ady, cdy, adx, -1.0),
              ab = two_products(adx, bdy, ady, bdx, -1.0);
  // Three products of 16-term expansions: 3 * 2 * 16 * 16 terms at most (12 KB on the stack).
  Expansion<3 * kProductTerms(16, 16)> det;
  add_product(det, alift, bc, 1.0);
  add_product(det, blift, ca, 1.0);
  add_product(det, clift, ab, 1.0);
  return sign_of(det);
}

}  // namespace

double orient2d_exact(const P2& a, const P2& b, const P2& c, double det) {
  return orient_exact(a, b, c) * (det == 0 ? 1.0 : std::fabs(det));
}

double incircle(const P2& a, const P2& b, const P2& c, const P2& d) {
  const double adx = a.x() - d.x(), ady = a.y() - d.y();
  const double bdx = b.x() - d.x(), bdy = b.y() - d.y();
  const double cdx = c.x() - d.x(), cdy = c.y() - d.y();
  const double bc = bdx * cdy - bdy * cdx, ca = cdx * ady - cdy * adx, ab = adx * bdy - ady * bdx;
  const double al = adx * adx + ady * ady, bl = bdx * bdx + bdy * bdy, cl = cdx * cdx + cdy * cdy;
  const double det = al * bc + bl * ca + cl * ab;
  const double perm = al * (std::fabs(bdx * cdy) + std::fabs(bdy * cdx)) + bl * (std::fabs(cdx * ady) + std::fabs(cdy * adx)) +
                      cl * (std::fabs(adx * bdy) + std::fabs(ady * bdx));
  if (std::fabs(det) > kIncircleBound * perm) return det;
  return incircle_exact(a, b, c, d) * (det == 0 ? 1.0 : std::fabs(det));
}

}  // namespace wefm::meshing
