#include "wefm/core/linalg/supernodal_refactor.hpp"

#include <algorithm>
#include <atomic>
#include <cstring>

#include "wefm/core/linalg/blas.hpp"
#include "wefm/core/sys/parallel.hpp"

namespace wefm {

void SupernodalRefactor::clear() {
  ready_ = false;
  f_ = SupernodalView();
  split_ = SupernodalSplit();
  std::vector<int>().swap(col_sn_);
  std::vector<std::int64_t>().swap(a_start_);
  std::vector<int>().swap(a_value_);
  std::vector<std::int64_t>().swap(a_pos_);
  std::vector<std::uint8_t>().swap(a_conj_);
}

bool SupernodalRefactor::prepare(const SupernodalView& f, const SpMatC& A) {
  clear();
  if (f.n <= 0 || f.nsuper <= 0 || !f.x || A.rows() != f.n || A.cols() != f.n || !A.isCompressed()) return false;
  f_ = f;
  const int n = f.n, ns = f.nsuper;
  col_sn_.resize(static_cast<size_t>(n));
  for (int sn = 0; sn < ns; ++sn)
    for (int c = f.super[sn]; c < f.super[sn + 1]; ++c) col_sn_[static_cast<size_t>(c)] = sn;
  std::vector<int> inv(static_cast<size_t>(n));
  for (int k = 0; k < n; ++k) inv[static_cast<size_t>(f.perm[k])] = k;
  // Each lower entry (r, c) of A lands at (i, j) = (inv r, inv c) of P A P^T, or conjugated at
  // (j, i) when that is above the diagonal.
  struct Target {
    int sn;
    std::int64_t pos;
  };
  auto target = [&](int i, int j, Target& t) {
    const int sn = col_sn_[static_cast<size_t>(j)];
    const int* rows = f.s + f.pi[sn];
    const int nr = f.pi[sn + 1] - f.pi[sn];
    const int* p = std::lower_bound(rows, rows + nr, i);
    if (p == rows + nr || *p != i) return false;
    t = {sn, static_cast<std::int64_t>(f.px[sn]) + static_cast<std::int64_t>(j - f.super[sn]) * nr + (p - rows)};
    return true;
  };
  std::vector<std::int64_t> count(static_cast<size_t>(ns) + 1, 0);
  std::vector<Target> where;
  std::vector<int> value;
  std::vector<std::uint8_t> conj;
  const int* outer = A.outerIndexPtr();
  const int* inner = A.innerIndexPtr();
  for (int c = 0; c < n; ++c)
    for (int v = outer[c]; v < outer[c + 1]; ++v) {
      const int r = inner[v];
      if (r < c) continue;
      int i = inv[static_cast<size_t>(r)], j = inv[static_cast<size_t>(c)];
      const bool flip = i < j;
      if (flip) std::swap(i, j);
      Target t;
      if (!target(i, j, t)) return false;
      where.push_back(t);
      value.push_back(v);
      conj.push_back(flip ? 1 : 0);
      ++count[static_cast<size_t>(t.sn) + 1];
    }
  for (int sn = 0; sn < ns; ++sn) count[static_cast<size_t>(sn) + 1] += count[static_cast<size_t>(sn)];
  a_start_ = count;
  a_value_.resize(value.size());
  a_pos_.resize(value.size());
  a_conj_.resize(value.size());
  for (size_t e = 0; e < value.size(); ++e) {
    const std::int64_t k = count[static_cast<size_t>(where[e].sn)]++;
    a_value_[static_cast<size_t>(k)] = value[e];
    a_pos_[static_cast<size_t>(k)] = where[e].pos;
    a_conj_[static_cast<size_t>(k)] = conj[e];
  }
  split_ = split_supernodal_tree(f);
  ready_ = true;
  return true;
}

bool SupernodalRefactor::factorize(const SpMatC& A, int threads) {
#ifndef WEFM_HAVE_CHOLMOD
  (void)A;
  (void)threads;
  return false;  // only CHOLMOD builds link the BLAS and LAPACK kernels (and have such factors)
#else
  if (!ready_) return false;
  const SupernodalView& f = f_;
  const int n = f.n, ns = f.nsuper;
  Complex* x = reinterpret_cast<Complex*>(f.x);
  const Complex* av = A.valuePtr();
  // Lists of the supernodes whose next update goes to each supernode, one per group that can
  // append to it: a group's own supernodes get only that group's; the ancestors get group 1's,
  // group 2's and their own, applied in that order.
  std::vector<std::vector<int>> lists[3];
  for (auto& l : lists) l.assign(static_cast<size_t>(ns), {});
  std::vector<int> next_row(static_cast<size_t>(ns), 0);  // per supernode: its first row not yet applied
  std::atomic<bool> positive{true};
  const bool split = !split_.empty();
  auto owner = [&](int sn) { return split ? split_.owner[static_cast<size_t>(sn)] : std::uint8_t(0); };

  // One group's pass (group 0 or 1, or 2 for the ancestors, or the whole factor when not split).
  auto run = [&](int grp, const std::vector<int>& order) {
    std::vector<int> map(static_cast<size_t>(n), -1);
    std::vector<Complex> c;
    const Complex one(1, 0), zero(0, 0);
    const double done = 1.0, dzero = 0.0;
    auto append = [&](int d, int t) {
      const std::uint8_t o = owner(t);
      const int list = o == 0 ? (grp == 2 || !split ? 2 : grp) : o - 1;
      lists[list][static_cast<size_t>(t)].push_back(d);
    };
    for (int sn : order) {
      if (!positive.load(std::memory_order_relaxed)) return;
      const int k1 = f.super[sn], k2 = f.super[sn + 1], nscol = k2 - k1;
      const int nsrow = f.pi[sn + 1] - f.pi[sn];
      const int* rows = f.s + f.pi[sn];
      Complex* ls = x + f.px[sn];
      std::fill(ls, ls + static_cast<std::int64_t>(nsrow) * nscol, Complex(0, 0));
      for (std::int64_t e = a_start_[static_cast<size_t>(sn)]; e < a_start_[static_cast<size_t>(sn) + 1]; ++e) {
        const Complex v = av[a_value_[static_cast<size_t>(e)]];
        x[a_pos_[static_cast<size_t>(e)]] = a_conj_[static_cast<size_t>(e)] ? std::conj(v) : v;
      }
      for (int i = 0; i < nsrow; ++i) map[static_cast<size_t>(rows[i])] = i;
      for (int list = 0; list < 3; ++list) {
        std::vector<int>& ds = lists[list][static_cast<size_t>(sn)];
        for (int d : ds) {
          const int dnscol = f.super[d + 1] - f.super[d], dnsrow = f.pi[d + 1] - f.pi[d];
          const int* drows = f.s + f.pi[d];
          const Complex* ld = x + f.px[d];
          const int p1 = next_row[static_cast<size_t>(d)];
          int p2 = p1;
          while (p2 < dnsrow && drows[p2] < k2) ++p2;
          const int ndcol = p2 - p1, ndrow = dnsrow - p1, ndrow2 = ndrow - ndcol;
          c.resize(static_cast<size_t>(ndrow) * static_cast<size_t>(ndcol));
          zherk_("L", "N", &ndcol, &dnscol, &done, ld + p1, &dnsrow, &dzero, c.data(), &ndrow);
          if (ndrow2 > 0) zgemm_("N", "C", &ndrow2, &ndcol, &dnscol, &one, ld + p2, &dnsrow, ld + p1, &dnsrow, &zero, c.data() + ndcol, &ndrow);
          for (int jj = 0; jj < ndcol; ++jj) {
            Complex* col = ls + static_cast<std::int64_t>(drows[p1 + jj] - k1) * nsrow;
            const Complex* cj = c.data() + static_cast<size_t>(jj) * static_cast<size_t>(ndrow);
            for (int ii = jj; ii < ndrow; ++ii) col[map[static_cast<size_t>(drows[p1 + ii])]] -= cj[ii];
          }
          next_row[static_cast<size_t>(d)] = p2;
          if (p2 < dnsrow) append(d, col_sn_[static_cast<size_t>(drows[p2])]);
        }
        std::vector<int>().swap(ds);
      }
      int info = 0;
      zpotrf_("L", &nscol, ls, &nsrow, &info);
      if (info != 0) {
        positive.store(false);
        return;
      }
      const int m = nsrow - nscol;
      if (m > 0) ztrsm_("R", "L", "C", "N", &m, &nscol, &one, ls, &nsrow, ls + nscol, &nsrow);
      next_row[static_cast<size_t>(sn)] = nscol;
      if (nsrow > nscol) append(sn, col_sn_[static_cast<size_t>(rows[nscol])]);
    }
  };
  if (split) {
    parallel_for(threads, 2, [&](Index g0, Index g1) {
      for (Index g = g0; g < g1; ++g) run(static_cast<int>(g), split_.group[g]);
    }, 1);
    if (positive.load()) run(2, split_.rest);
  } else {
    std::vector<int> all(static_cast<size_t>(ns));
    for (int sn = 0; sn < ns; ++sn) all[static_cast<size_t>(sn)] = sn;
    run(2, all);
  }
  return positive.load();
#endif
}

}  // namespace wefm
