#include "wefm/core/method/energy_assembler.hpp"
#include "wefm/core/method/energy.hpp"
#include "wefm/core/sys/huge_pages.hpp"

#include <algorithm>

#include "wefm/core/sys/parallel.hpp"

namespace wefm {

namespace {

// Columns per block of the pattern build: each block's rows are collected by one thread and the
// blocks laid end to end afterwards.
constexpr Index kColumnBlock = 8192;

}  // namespace

EnergyAssembler::EnergyAssembler(const Topology& tp, const SpMatC* B, int threads) : tp_(&tp), uc_(use_corners(tp)) {
  const Index n = tp.use_count;
  btb_ = boundary_gram(B);
  const bool with_b = btb_.nonZeros() > 0;
  // Rows of column u: the uses of every triangle at a corner of u, and B^H B's rows.
  const Index blocks = (n + kColumnBlock - 1) / kColumnBlock;
  std::vector<std::vector<int>> block_rows(static_cast<size_t>(blocks));
  std::vector<int> count(static_cast<size_t>(n), 0);
  parallel_for(
      threads, blocks,
      [&](Index b0, Index b1) {
        std::vector<int> rows;
        std::vector<Index> seen(static_cast<size_t>(n), -1);  // seen[r] == u: r is already a row of column u
        for (Index b = b0; b < b1; ++b) {
          std::vector<int>& out = block_rows[static_cast<size_t>(b)];
          for (Index u = b * kColumnBlock; u < std::min(n, (b + 1) * kColumnBlock); ++u) {
            rows.clear();
            auto add = [&](Index r) {
              if (seen[static_cast<size_t>(r)] == u) return;
              seen[static_cast<size_t>(r)] = u;
              rows.push_back(r);
            };
            for (Index q = uc_.start[static_cast<size_t>(u)]; q < uc_.start[static_cast<size_t>(u) + 1]; ++q) {
              const Index t3 = uc_.corner[static_cast<size_t>(q)] / 3 * 3;
              for (Index r = 0; r < 3; ++r) add(tp.corner_use[static_cast<size_t>(t3 + r)]);
            }
            if (with_b)
              for (SpMatC::InnerIterator it(btb_, u); it; ++it) add(static_cast<Index>(it.row()));
            if (rows.size() <= 32) {  // a one-ring: insertion sort
              for (size_t i = 1; i < rows.size(); ++i)
                for (size_t j = i; j > 0 && rows[j] < rows[j - 1]; --j) std::swap(rows[j], rows[j - 1]);
            } else {
              std::sort(rows.begin(), rows.end());
            }
            count[static_cast<size_t>(u)] = static_cast<int>(rows.size());
            out.insert(out.end(), rows.begin(), rows.end());
          }
        }
      },
      1);
  outer_.assign(static_cast<size_t>(n) + 1, 0);
  for (Index u = 0; u < n; ++u) outer_[static_cast<size_t>(u) + 1] = outer_[static_cast<size_t>(u)] + count[static_cast<size_t>(u)];
  assign_huge(row_, static_cast<size_t>(outer_.back()));
  assign_huge(slot_, 3 * tp.corner_use.size());
  btb_slot_.resize(static_cast<size_t>(btb_.nonZeros()));
  // Lay the blocks out and find every contribution's slot by a search in its (short) column.
  parallel_for(
      threads, blocks,
      [&](Index b0, Index b1) {
        for (Index b = b0; b < b1; ++b) {
          const Index u0 = b * kColumnBlock, u1 = std::min(n, (b + 1) * kColumnBlock);
          std::vector<int>& rows = block_rows[static_cast<size_t>(b)];
          std::copy(rows.begin(), rows.end(), row_.begin() + outer_[static_cast<size_t>(u0)]);
          rows = std::vector<int>{};
          for (Index u = u0; u < u1; ++u) {
            const auto first = row_.begin() + outer_[static_cast<size_t>(u)], last = row_.begin() + outer_[static_cast<size_t>(u) + 1];
            auto slot_of = [&](int r) { return static_cast<int>(std::lower_bound(first, last, r) - row_.begin()); };
            for (Index q = uc_.start[static_cast<size_t>(u)]; q < uc_.start[static_cast<size_t>(u) + 1]; ++q) {
              const Index c = uc_.corner[static_cast<size_t>(q)], t3 = c / 3 * 3;
              for (Index r = 0; r < 3; ++r)
                slot_[3 * static_cast<size_t>(c) + static_cast<size_t>(r)] = slot_of(tp.corner_use[static_cast<size_t>(t3 + r)]);
            }
            if (with_b)
              for (int p = btb_.outerIndexPtr()[u]; p < btb_.outerIndexPtr()[u + 1]; ++p)
                btb_slot_[static_cast<size_t>(p)] = slot_of(btb_.innerIndexPtr()[p]);
          }
        }
      },
      1);
}

bool EnergyAssembler::set_boundary(const SpMatC* B) {
  const SpMatC btb = boundary_gram(B);
  const bool same = btb.nonZeros() == btb_.nonZeros() && (btb.nonZeros() == 0 || (btb.cols() == btb_.cols() &&
                    std::equal(btb.outerIndexPtr(), btb.outerIndexPtr() + btb.cols() + 1, btb_.outerIndexPtr()) &&
                    std::equal(btb.innerIndexPtr(), btb.innerIndexPtr() + btb.nonZeros(), btb_.innerIndexPtr())));
  if (!same) return false;
  if (btb.nonZeros()) std::copy(btb.valuePtr(), btb.valuePtr() + btb.nonZeros(), btb_.valuePtr());
  return true;
}

namespace {

// Column `col` of triangle t3/3's block: entry r = sum over its half-edges j of
// w_j conj(a_j[r]) a_j[col], where half-edge j predicts corner j+2 from its base j -> j+1 with
// coefficients 1 at corner j+2, -(1 - sigma_j) at j and -sigma_j at j+1 (METHOD §5).
// conj(x) y is formed in reals so that entry (r, c) and (c, r) are exact conjugates.
inline void block_column(const double* w, const Complex* sigma, Index col, Complex v[3]) {
  Complex a[3][3];
  for (Index j = 0; j < 3; ++j) {
    a[j][j] = -(1.0 - sigma[j]);
    a[j][(j + 1) % 3] = -sigma[j];
    a[j][(j + 2) % 3] = Complex(1, 0);
  }
  for (Index r = 0; r < 3; ++r) {
    double re = 0.0, im = 0.0;
    for (Index j = 0; j < 3; ++j) {
      const Complex x = a[j][r], y = a[j][col];
      re += w[j] * (x.real() * y.real() + x.imag() * y.imag());
      im += w[j] * (x.real() * y.imag() - x.imag() * y.real());
    }
    v[r] = Complex(re, im);
  }
}

}  // namespace

SpMatC EnergyAssembler::assemble(const std::vector<double>& w, const std::vector<Complex>& sigma, int threads) const {
  const Topology& tp = *tp_;
  const Index n = tp.use_count;
  const Index nt = static_cast<Index>(tp.corner_use.size() / 3);
  SpMatC K(n, n);
  K.resizeNonZeros(static_cast<Index>(row_.size()));
  advise_huge_pages_sparse(K);
  std::copy(outer_.begin(), outer_.end(), K.outerIndexPtr());
  std::copy(row_.begin(), row_.end(), K.innerIndexPtr());
  Complex* value = K.valuePtr();
  auto add_btb = [&](Index u) {
    for (int p = btb_.outerIndexPtr()[u]; p < btb_.outerIndexPtr()[u + 1]; ++p) value[btb_slot_[static_cast<size_t>(p)]] += btb_.valuePtr()[p];
  };
  if (threads <= 1) {
    // One thread: triangles in order, each block scattered to its slots. Every entry receives its
    // terms in ascending triangle order, then B^H B's: the order of the gather below, so the bits
    // are the same, with the per-triangle data read sequentially.
    std::fill(value, value + row_.size(), Complex(0, 0));
    for (Index t = 0; t < nt; ++t)
      for (Index col = 0; col < 3; ++col) {
        Complex v[3];
        block_column(&w[3 * static_cast<size_t>(t)], &sigma[3 * static_cast<size_t>(t)], col, v);
        const int* slot = &slot_[9 * static_cast<size_t>(t) + 3 * static_cast<size_t>(col)];
        for (Index r = 0; r < 3; ++r) value[slot[r]] += v[r];
      }
    if (btb_.nonZeros())
      for (Index u = 0; u < n; ++u) add_btb(u);
    return K;
  }
  // Threads: each column gathers its blocks in ascending corner (= triangle) order, then B^H B's.
  parallel_for(threads, n, [&](Index u0, Index u1) {
    std::fill(value + outer_[static_cast<size_t>(u0)], value + outer_[static_cast<size_t>(u1)], Complex(0, 0));
    for (Index u = u0; u < u1; ++u) {
      for (Index q = uc_.start[static_cast<size_t>(u)]; q < uc_.start[static_cast<size_t>(u) + 1]; ++q) {
        const Index c = uc_.corner[static_cast<size_t>(q)], t3 = c / 3 * 3;
        Complex v[3];
        block_column(&w[static_cast<size_t>(t3)], &sigma[static_cast<size_t>(t3)], c - t3, v);
        for (Index r = 0; r < 3; ++r) value[slot_[3 * static_cast<size_t>(c) + static_cast<size_t>(r)]] += v[r];
      }
      if (btb_.nonZeros()) add_btb(u);
    }
  });
  return K;
}

}  // namespace wefm
