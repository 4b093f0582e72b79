#include "wefm/core/meshing/predicates.hpp"

#include <cmath>
#include <limits>
#include <vector>

namespace wefm::meshing {
namespace {

// Exact arithmetic on expansions: sums of non-overlapping doubles in increasing magnitude, built
// from error-free transformations. fma gives the exact product error in one step.
using Expansion = std::vector<double>;

inline void two_sum(double a, double b, double& s, double& e) {
  s = a + b;
  const double bv = s - a, av = s - bv;
  e = (a - av) + (b - bv);
}

Expansion from_diff(double a, double b) {
  double s, e;
  two_sum(a, -b, s, e);
  return {e, s};
}

Expansion grow(const Expansion& x, double b) {
  Expansion out;
  out.reserve(x.size() + 1);
  double q = b;
  for (double xi : x) {
    double s, e;
    two_sum(q, xi, s, e);
    if (e != 0) out.push_back(e);
    q = s;
  }
  out.push_back(q);
  return out;
}

Expansion add(const Expansion& x, const Expansion& y) {
  Expansion r = x;
  for (double v : y) r = grow(r, v);
  return r;
}

Expansion scale(const Expansion& x, double b) {
  Expansion r;
  for (double xi : x) {
    const double p = xi * b;
    const double e = std::fma(xi, b, -p);
    r = grow(r, e);
    r = grow(r, p);
  }
  return r;
}

Expansion mul(const Expansion& x, const Expansion& y) {
  Expansion r;
  for (double v : y) r = add(r, scale(x, v));
  return r;
}

Expansion neg(Expansion x) {
  for (double& v : x) v = -v;
  return x;
}

double sign_of(const Expansion& x) {
  for (auto it = x.rbegin(); it != x.rend(); ++it)
    if (*it != 0) return *it > 0 ? 1.0 : -1.0;
  return 0.0;
}

constexpr double kEps = std::numeric_limits<double>::epsilon() * 0.5;
// Error bound coefficient chosen generously above Shewchuk's (10+96e)e (orient2d's is in the header).
constexpr double kIncircleBound = 12.0 * kEps;

double orient_exact(const P2& a, const P2& b, const P2& c) {
  const Expansion acx = from_diff(a.x(), c.x()), acy = from_diff(a.y(), c.y());
  const Expansion bcx = from_diff(b.x(), c.x()), bcy = from_diff(b.y(), c.y());
  return sign_of(add(mul(acx, bcy), neg(mul(acy, bcx))));
}

double incircle_exact(const P2& a, const P2& b, const P2& c, const P2& d) {
  const Expansion adx = from_diff(a.x(), d.x()), ady = from_diff(a.y(), d.y());
  const Expansion bdx = from_diff(b.x(), d.x()), bdy = from_diff(b.y(), d.y());
  const Expansion cdx = from_diff(c.x(), d.x()), cdy = from_diff(c.y(), d.y());
  const Expansion alift = add(mul(adx, adx), mul(ady, ady));
  const Expansion blift = add(mul(bdx, bdx), mul(bdy, bdy));
  const Expansion clift = add(mul(cdx, cdx), mul(cdy, cdy));
  const Expansion bc = add(mul(bdx, cdy), neg(mul(bdy, cdx)));
  const Expansion ca = add(mul(cdx, ady), neg(mul(cdy, adx)));
  const Expansion ab = add(mul(adx, bdy), neg(mul(ady, bdx)));
  return sign_of(add(add(mul(alift, bc), mul(blift, ca)), mul(clift, ab)));
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
