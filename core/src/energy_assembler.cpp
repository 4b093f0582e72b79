#include "wefm/core/energy_assembler.hpp"

#include <algorithm>

#include "wefm/core/parallel.hpp"

namespace wefm {

namespace {

// Columns per block of the pattern build: each block's rows are collected by one thread and the
// blocks laid end to end afterwards.
constexpr Index kColumnBlock = 8192;

}  // namespace

EnergyAssembler::EnergyAssembler(const Topology& tp, const SpMatC* B, int threads) : tp_(&tp), uc_(use_corners(tp)) {
  const Index n = tp.use_count;
  if (B && B->nonZeros()) {
    btb_ = SpMatC(B->adjoint()) * (*B);
    btb_.makeCompressed();
  }
  const bool with_b = btb_.nonZeros() > 0;
  // Rows of column u: the uses of every triangle at a corner of u, and B^H B's rows.
  const Index blocks = (n + kColumnBlock - 1) / kColumnBlock;
  std::vector<std::vector<int>> block_rows(static_cast<size_t>(blocks));
  std::vector<int> count(static_cast<size_t>(n), 0);
  parallel_for(
      threads, blocks,
      [&](Index b0, Index b1) {
        std::vector<int> rows;
        for (Index b = b0; b < b1; ++b) {
          std::vector<int>& out = block_rows[static_cast<size_t>(b)];
          for (Index u = b * kColumnBlock; u < std::min(n, (b + 1) * kColumnBlock); ++u) {
            rows.clear();
            for (Index q = uc_.start[static_cast<size_t>(u)]; q < uc_.start[static_cast<size_t>(u) + 1]; ++q) {
              const Index t3 = uc_.corner[static_cast<size_t>(q)] / 3 * 3;
              for (Index r = 0; r < 3; ++r) rows.push_back(tp.corner_use[static_cast<size_t>(t3 + r)]);
            }
            if (with_b)
              for (SpMatC::InnerIterator it(btb_, u); it; ++it) rows.push_back(static_cast<int>(it.row()));
            std::sort(rows.begin(), rows.end());
            rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
            count[static_cast<size_t>(u)] = static_cast<int>(rows.size());
            out.insert(out.end(), rows.begin(), rows.end());
          }
        }
      },
      1);
  outer_.assign(static_cast<size_t>(n) + 1, 0);
  for (Index u = 0; u < n; ++u) outer_[static_cast<size_t>(u) + 1] = outer_[static_cast<size_t>(u)] + count[static_cast<size_t>(u)];
  row_.resize(static_cast<size_t>(outer_.back()));
  slot_.resize(3 * tp.corner_use.size());
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

SpMatC EnergyAssembler::assemble(const std::vector<double>& w, const std::vector<Complex>& sigma, int threads) const {
  const Topology& tp = *tp_;
  const Index n = tp.use_count;
  SpMatC K(n, n);
  K.resizeNonZeros(static_cast<Index>(row_.size()));
  std::copy(outer_.begin(), outer_.end(), K.outerIndexPtr());
  std::copy(row_.begin(), row_.end(), K.innerIndexPtr());
  Complex* value = K.valuePtr();
  parallel_for(threads, n, [&](Index u0, Index u1) {
    std::fill(value + outer_[static_cast<size_t>(u0)], value + outer_[static_cast<size_t>(u1)], Complex(0, 0));
    for (Index u = u0; u < u1; ++u) {
      for (Index q = uc_.start[static_cast<size_t>(u)]; q < uc_.start[static_cast<size_t>(u) + 1]; ++q) {
        const Index c = uc_.corner[static_cast<size_t>(q)], t3 = c / 3 * 3, col = c - t3;
        // Half-edge j of the triangle predicts corner j+2 from its base j -> j+1: coefficients
        // 1 at corner j+2, -(1 - sigma) at j, -sigma at j+1 (METHOD §5), weight w.
        Complex a[3][3];
        for (Index j = 0; j < 3; ++j) {
          const Complex s = sigma[static_cast<size_t>(t3 + j)];
          a[j][j] = -(1.0 - s);
          a[j][(j + 1) % 3] = -s;
          a[j][(j + 2) % 3] = Complex(1, 0);
        }
        for (Index r = 0; r < 3; ++r) {
          Complex v(0, 0);
          for (Index j = 0; j < 3; ++j) v += w[static_cast<size_t>(t3 + j)] * (std::conj(a[j][r]) * a[j][col]);
          value[slot_[3 * static_cast<size_t>(c) + static_cast<size_t>(r)]] += v;
        }
      }
      if (btb_.nonZeros())
        for (int p = btb_.outerIndexPtr()[u]; p < btb_.outerIndexPtr()[u + 1]; ++p)
          value[btb_slot_[static_cast<size_t>(p)]] += btb_.valuePtr()[p];
    }
  });
  return K;
}

}  // namespace wefm
