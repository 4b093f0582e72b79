#include "wefm/core/linalg/supernodal_inverse.hpp"

#include <Eigen/Dense>
#include <algorithm>

#include "wefm/core/sys/error.hpp"
#include "wefm/core/linalg/blas.hpp"
#include "wefm/core/sys/parallel.hpp"

namespace wefm {

#ifdef WEFM_HAVE_CHOLMOD
namespace {
constexpr int kBlock = 64;  // right-hand sides per BLAS call

// The supernodal elimination tree: each column's position in the factor (invp), each factor
// column's supernode, and each supernode's parent (-1: a root).
struct Tree {
  std::vector<int> invp, snode_of, parent;
};

Tree supernode_tree(const SupernodalView& f) {
  const int n = f.n, ns = f.nsuper;
  Tree tr;
  tr.invp.resize(static_cast<size_t>(n));
  tr.snode_of.resize(static_cast<size_t>(n));
  tr.parent.resize(static_cast<size_t>(ns));
  for (int k = 0; k < n; ++k) tr.invp[static_cast<size_t>(f.perm ? f.perm[k] : k)] = k;
  for (int j = 0; j < ns; ++j)
    for (int k = f.super[j]; k < f.super[j + 1]; ++k) tr.snode_of[static_cast<size_t>(k)] = j;
  for (int j = 0; j < ns; ++j) {
    const int nscol = f.super[j + 1] - f.super[j], nsrow = f.pi[j + 1] - f.pi[j];
    // The first row below a supernode's own columns lies in its parent (CHOLMOD's supernodal tree).
    tr.parent[static_cast<size_t>(j)] = nsrow > nscol ? tr.snode_of[static_cast<size_t>(f.s[f.pi[j] + nscol])] : -1;
  }
  return tr;
}

// Per supernode, the targets whose path passes through it (R[rstart[j] .. rstart[j] + count[j]),
// ascending: filled in target order), and the block of their forward solves on its columns (X
// from boff[j], a column per target), started at the unit vectors.
struct Paths {
  std::vector<std::size_t> count, rstart, boff;
  std::vector<int> R;
  Eigen::VectorXcd X;
};

// The targets' paths; counted first, so that a deep tree is refused (false) before anything large
// is allocated.
bool target_paths(const SupernodalView& f, const Tree& tr, const std::vector<Index>& target, std::size_t max_entries, Paths& p) {
  const int ns = f.nsuper;
  const size_t m = target.size();
  auto first_snode = [&](size_t t) { return tr.snode_of[static_cast<size_t>(tr.invp[static_cast<size_t>(target[t])])]; };
  p.count.assign(static_cast<size_t>(ns) + 1, 0);
  std::size_t entries = m * m;
  for (size_t t = 0; t < m; ++t)
    for (int j = first_snode(t); j >= 0; j = tr.parent[static_cast<size_t>(j)]) {
      ++p.count[static_cast<size_t>(j)];
      entries += static_cast<size_t>(f.super[j + 1] - f.super[j]);
      if (entries > max_entries) return false;
    }
  p.rstart.assign(static_cast<size_t>(ns) + 1, 0);
  p.boff.assign(static_cast<size_t>(ns) + 1, 0);
  for (int j = 0; j < ns; ++j) {
    p.rstart[static_cast<size_t>(j) + 1] = p.rstart[static_cast<size_t>(j)] + p.count[static_cast<size_t>(j)];
    p.boff[static_cast<size_t>(j) + 1] = p.boff[static_cast<size_t>(j)] + p.count[static_cast<size_t>(j)] * static_cast<size_t>(f.super[j + 1] - f.super[j]);
  }
  p.R.resize(p.rstart[static_cast<size_t>(ns)]);
  std::vector<std::size_t> fill(p.rstart.begin(), p.rstart.end() - 1);
  p.X = Eigen::VectorXcd::Zero(static_cast<Index>(p.boff[static_cast<size_t>(ns)]));
  for (size_t t = 0; t < m; ++t) {
    const int j0 = first_snode(t);
    const size_t q0 = fill[static_cast<size_t>(j0)] - p.rstart[static_cast<size_t>(j0)];
    const int nscol0 = f.super[j0 + 1] - f.super[j0];
    p.X[static_cast<Index>(p.boff[static_cast<size_t>(j0)] + q0 * static_cast<size_t>(nscol0) +
                           static_cast<size_t>(tr.invp[static_cast<size_t>(target[t])] - f.super[j0]))] = 1.0;
    for (int j = j0; j >= 0; j = tr.parent[static_cast<size_t>(j)]) p.R[fill[static_cast<size_t>(j)]++] = static_cast<int>(t);
  }
  return true;
}

// Supernode j's forward solves of its targets, their products added to G (y_a^H y_b, lower
// triangle), and the rows below scattered into the ancestors' blocks. H, U and pos are buffers.
void solve_supernode(const SupernodalView& f, const Tree& tr, Paths& p, int j, int threads, Eigen::MatrixXcd& G, Eigen::MatrixXcd& H,
                     Eigen::MatrixXcd& U, std::vector<int>& pos) {
  const Complex one(1, 0), zero(0, 0);
  const double done = 1, dzero = 0;
  const int r = static_cast<int>(p.count[static_cast<size_t>(j)]);
  const int nscol = f.super[j + 1] - f.super[j], nsrow = f.pi[j + 1] - f.pi[j], nb = nsrow - nscol;
  const int* Rj = p.R.data() + p.rstart[static_cast<size_t>(j)];
  Complex* Xj = p.X.data() + p.boff[static_cast<size_t>(j)];
  const Complex* Lj = reinterpret_cast<const Complex*>(f.x) + f.px[j];
  const int* rowidx = f.s + f.pi[j] + nscol;
  H.resize(r, r);
  if (nb > 0) U.resize(nb, r);
  // Right-hand sides in blocks of a fixed width, whatever the thread count: each block's
  // arithmetic is the same however the blocks are shared out.
  const int nblk = (r + kBlock - 1) / kBlock;
  parallel_for(threads, nblk, [&](Index b0, Index b1) {
    for (Index blk = b0; blk < b1; ++blk) {
      const int c0 = static_cast<int>(blk) * kBlock, w = std::min(kBlock, r - c0);
      Complex* xb = Xj + static_cast<size_t>(c0) * static_cast<size_t>(nscol);
      // Every descendant on the paths has updated Xj already (supernodes come in postorder).
      ztrsm_("L", "L", "N", "N", &nscol, &w, &one, Lj, &nsrow, xb, &nscol);
      if (nb > 0) zgemm_("N", "N", &nb, &w, &nscol, &one, Lj + nscol, &nsrow, xb, &nscol, &zero, U.data() + static_cast<size_t>(c0) * nb, &nb);
    }
  }, 1);
  // H = Xj^H Xj, lower triangle, by the same blocks of columns (its diagonal block and the rows
  // below it).
  parallel_for(threads, nblk, [&](Index b0, Index b1) {
    for (Index blk = b0; blk < b1; ++blk) {
      const int c0 = static_cast<int>(blk) * kBlock, w = std::min(kBlock, r - c0), below = r - c0 - w;
      const Complex* xb = Xj + static_cast<size_t>(c0) * static_cast<size_t>(nscol);
      Complex* hb = H.data() + static_cast<size_t>(c0) * r + c0;
      zherk_("L", "C", &w, &nscol, &done, xb, &nscol, &dzero, hb, &r);
      if (below > 0) zgemm_("C", "N", &below, &w, &nscol, &one, xb + static_cast<size_t>(w) * nscol, &nscol, xb, &nscol, &zero, hb + w, &r);
      for (int b = c0; b < c0 + w; ++b)
        for (int a = b; a < r; ++a) G(Rj[a], Rj[b]) += H(a, b);  // Rj ascending: stays in G's lower triangle
    }
  }, 1);
  if (nb == 0) return;
  // The rows below fall into ancestors in runs (row indices ascend); each ancestor's targets
  // include all of this supernode's, so a column of Xj scatters into a column of the ancestor's.
  for (int i0 = 0; i0 < nb;) {
    const int a = tr.snode_of[static_cast<size_t>(rowidx[i0])];
    int i1 = i0 + 1;
    while (i1 < nb && rowidx[i1] < f.super[a + 1]) ++i1;
    const int* Ra = p.R.data() + p.rstart[static_cast<size_t>(a)];
    const int ra = static_cast<int>(p.count[static_cast<size_t>(a)]);
    pos.resize(static_cast<size_t>(r));
    for (int q = 0; q < r; ++q) pos[static_cast<size_t>(q)] = static_cast<int>(std::lower_bound(Ra, Ra + ra, Rj[q]) - Ra);
    const int nacol = f.super[a + 1] - f.super[a];
    Complex* Xa = p.X.data() + p.boff[static_cast<size_t>(a)];
    parallel_for(threads, r, [&](Index q0, Index q1) {
      for (Index q = q0; q < q1; ++q) {
        Complex* col = Xa + static_cast<size_t>(pos[static_cast<size_t>(q)]) * static_cast<size_t>(nacol);
        const Complex* uq = U.data() + static_cast<size_t>(q) * nb;
        for (int i = i0; i < i1; ++i) col[rowidx[i] - f.super[a]] -= uq[i];
      }
    }, 64);
    i0 = i1;
  }
}

}  // namespace

bool supernodal_inverse_entries(const SupernodalView& f, const std::vector<Index>& rows, const std::vector<Index>& cols,
                                std::size_t max_entries, int threads, Eigen::MatrixXcd& out) {
  out.resize(0, 0);
  std::vector<Index> target(rows);
  target.insert(target.end(), cols.begin(), cols.end());
  std::sort(target.begin(), target.end());
  target.erase(std::unique(target.begin(), target.end()), target.end());
  if (!target.empty() && (target.front() < 0 || target.back() >= f.n)) fail(Errc::internal, "inverse entry out of range");
  const size_t m = target.size();
  if (m * m > max_entries) return false;

  const Tree tr = supernode_tree(f);
  Paths p;
  if (!target_paths(f, tr, target, max_entries, p)) return false;
  Eigen::MatrixXcd G = Eigen::MatrixXcd::Zero(static_cast<Index>(m), static_cast<Index>(m));  // lower triangle
  Eigen::MatrixXcd H, U;
  std::vector<int> pos;
  for (int j = 0; j < f.nsuper; ++j)
    if (p.count[static_cast<size_t>(j)] > 0) solve_supernode(f, tr, p, j, threads, G, H, U, pos);

  auto index_of = [&](Index a) { return static_cast<Index>(std::lower_bound(target.begin(), target.end(), a) - target.begin()); };
  out.resize(static_cast<Index>(rows.size()), static_cast<Index>(cols.size()));
  for (size_t c = 0; c < cols.size(); ++c) {
    const Index tc = index_of(cols[c]);
    for (size_t q = 0; q < rows.size(); ++q) {
      const Index tq = index_of(rows[q]);
      out(static_cast<Index>(q), static_cast<Index>(c)) = tq >= tc ? G(tq, tc) : std::conj(G(tc, tq));
    }
  }
  return true;
}
#else
bool supernodal_inverse_entries(const SupernodalView&, const std::vector<Index>&, const std::vector<Index>&, std::size_t, int,
                                Eigen::MatrixXcd& out) {
  out.resize(0, 0);
  return false;
}
#endif

}  // namespace wefm
