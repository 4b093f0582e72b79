#include "wefm/core/method/energy.hpp"
#include "wefm/core/sys/huge_pages.hpp"

#include <algorithm>
#include <cmath>

#include "wefm/core/method/energy_assembler.hpp"
#include "wefm/core/sys/parallel.hpp"
#include "wefm/core/mesh/use_corners.hpp"

namespace wefm {

namespace {

// w_h of eq. 9 with the per-use sums gathered in corner order: the same additions, in the same order,
// as a scatter over ascending half-edges, and one pow per use instead of one per half-edge.
std::vector<double> weights(const Topology& tp, const Coefficients& c, double k, const UseCorners& uc, int threads) {
  const Index nh = static_cast<Index>(c.alpha.size());
  std::vector<double> scale(static_cast<size_t>(tp.use_count));
  parallel_for(threads, tp.use_count, [&](Index u0, Index u1) {
    for (Index u = u0; u < u1; ++u) {
      double inv_sum = 0.0;  // over the half-edges opposite the use's corners
      for (Index q = uc.start[static_cast<size_t>(u)]; q < uc.start[static_cast<size_t>(u) + 1]; ++q)
        inv_sum += 1.0 / c.beta[static_cast<size_t>(HalfEdges::next(uc.corner[static_cast<size_t>(q)]))];
      scale[static_cast<size_t>(u)] = std::pow(inv_sum, -k);
    }
  });
  std::vector<double> w;
  assign_huge(w, static_cast<size_t>(nh));
  parallel_for(threads, nh, [&](Index h0, Index h1) {
    for (Index h = h0; h < h1; ++h)
      w[static_cast<size_t>(h)] = (1.0 / c.beta[static_cast<size_t>(h)]) *
                                  scale[static_cast<size_t>(tp.corner_use[static_cast<size_t>(HalfEdges::prev(h))])];
  });
  return w;
}

// Rows of a column-major matrix, each row's entries in ascending column order (counting transpose).
struct RowMajor {
  std::vector<int> start, col;
  std::vector<Complex> val;
};

RowMajor rows_of(const SpMatC& M) {
  RowMajor r;
  r.start.assign(static_cast<size_t>(M.rows()) + 1, 0);
  for (Index j = 0; j < M.outerSize(); ++j)
    for (SpMatC::InnerIterator it(M, j); it; ++it) ++r.start[static_cast<size_t>(it.row()) + 1];
  for (size_t i = 1; i < r.start.size(); ++i) r.start[i] += r.start[i - 1];
  r.col.resize(static_cast<size_t>(r.start.back()));
  r.val.resize(r.col.size());
  std::vector<int> fill(r.start.begin(), r.start.end() - 1);
  for (Index j = 0; j < M.outerSize(); ++j)
    for (SpMatC::InnerIterator it(M, j); it; ++it) {
      const size_t q = static_cast<size_t>(fill[static_cast<size_t>(it.row())]++);
      r.col[q] = static_cast<int>(j);
      r.val[q] = it.value();
    }
  return r;
}

// Columns of K per block, computed by one thread: what the block contributes, before the blocks are
// laid end to end.
struct ColumnBlock {
  std::vector<int> count, row;
  std::vector<Complex> val;
};

constexpr Index kColumnBlock = 8192;

}  // namespace

std::vector<Complex> compute_sigma(const Coefficients& c, const std::vector<double>& rho, double s, int threads) {
  std::vector<Complex> sigma;
  assign_huge(sigma, c.alpha.size());
  const bool use_rho = s != 0.0 && !rho.empty();
  parallel_for(threads, static_cast<Index>(sigma.size()), [&](Index h0, Index h1) {
    for (size_t h = static_cast<size_t>(h0); h < static_cast<size_t>(h1); ++h)
      sigma[h] = Complex(c.alpha[h], c.beta[h] * (use_rho ? std::pow(rho[h], s) : 1.0));
  });
  return sigma;
}

std::vector<double> compute_weights(const Topology& tp, const Coefficients& c, double k, int threads) {
  return weights(tp, c, k, use_corners(tp), threads);
}

SpMatC assemble_surface_operator(const Topology& tp, const Coefficients& c, const std::vector<Complex>& sigma, double k, Residual form,
                                 int threads) {
  const Index n = tp.use_count;
  const size_t nh = c.alpha.size();
  const UseCorners uc = use_corners(tp);
  const std::vector<double> w = weights(tp, c, k, uc, threads);
  if (form == Residual::PerHalfEdge) {
    // Row h holds its triangle's three uses, so column u holds the three rows of every triangle at a
    // corner of u: the pattern follows from the use's corners without triplets or sorting (rows
    // ascend because corners do; the uses of one triangle are distinct vertices).
    SpMatC A(static_cast<Index>(nh), n);
    A.resizeNonZeros(static_cast<Index>(3 * nh));
    int* outer = A.outerIndexPtr();
    for (Index u = 0; u <= n; ++u) outer[u] = 3 * uc.start[static_cast<size_t>(u)];
    int* inner = A.innerIndexPtr();
    Complex* value = A.valuePtr();
    parallel_for(threads, n, [&](Index u0, Index u1) {
      for (Index u = u0; u < u1; ++u) {
        size_t q = static_cast<size_t>(outer[u]);
        for (Index p = uc.start[static_cast<size_t>(u)]; p < uc.start[static_cast<size_t>(u) + 1]; ++p) {
          const Index corner = uc.corner[static_cast<size_t>(p)];
          for (Index h = corner - corner % 3; h < corner - corner % 3 + 3; ++h, ++q) {
            const double sw = std::sqrt(w[static_cast<size_t>(h)]);
            inner[q] = h;
            if (corner == HalfEdges::prev(h)) value[q] = Complex(sw, 0);               // the use predicted
            else if (corner == h) value[q] = -sw * (1.0 - sigma[static_cast<size_t>(h)]);  // base start
            else value[q] = -sw * sigma[static_cast<size_t>(h)];                      // base end
          }
        }
      }
    });
    return A;
  }
  std::vector<Eigen::Triplet<Complex>> trip;
  trip.reserve(nh * 3);
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

namespace {

// With c null: the pattern only (every value 1), from the mesh and the loops alone.
SpMatC boundary_operator(const TriMesh& m, const Topology& tp, const Coefficients* c, double mu, double unwind) {
  const Index n = tp.use_count;
  std::vector<Eigen::Triplet<Complex>> trip;
  Index row = 0;
  const double inv = c ? 1.0 / c->length_scale : 1.0;
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
      turn[j] = c ? kPi - c->use_angle[static_cast<size_t>(lu[j])] : 0.0;
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
      const Complex cm = c ? scale * (Lp / lbar) * std::polar(1.0, phi) : Complex(1, 0), cp = c ? scale * (Lm / lbar) * std::polar(1.0, -phi) : Complex(1, 0);
      trip.emplace_back(row, up, cm);
      trip.emplace_back(row, un, cp);
      trip.emplace_back(row, u, c ? -(cm + cp) : Complex(1, 0));
      ++row;
    }
  }
  SpMatC B(row, n);
  B.setFromTriplets(trip.begin(), trip.end());
  return B;
}

}  // namespace

SpMatC assemble_boundary_operator(const TriMesh& m, const Topology& tp, const Coefficients& c, double mu, double unwind) {
  return boundary_operator(m, tp, &c, mu, unwind);
}

SpMatC boundary_operator_pattern(const TriMesh& m, const Topology& tp, double mu) { return boundary_operator(m, tp, nullptr, mu, 1.0); }

SpMatC boundary_gram(const SpMatC* B) {
  SpMatC btb;
  if (B && B->nonZeros()) {
    btb = SpMatC(B->adjoint()) * (*B);
    btb.makeCompressed();
  }
  return btb;
}

SpMatC assemble_energy(const SpMatC& A, const SpMatC* B, int threads) {
  // K = A^H A + B^H B column by column (Gustavson): K(:, j) = sum over the rows r of column j of
  // conj(row r) * M(r, j), rows in ascending order, A's and B's sums kept apart and added last, as
  // Eigen's product-then-sum did, so K has the bits it had. Every column is one thread's work in a
  // fixed order, so K is bit-identical for any thread count, and no product, adjoint copy or sum of
  // matrices is materialised.
  const Index n = A.cols();
  const bool with_b = B && B->nonZeros();
  const RowMajor ar = rows_of(A);
  const RowMajor br = with_b ? rows_of(*B) : RowMajor{};
  const Index blocks = (n + kColumnBlock - 1) / kColumnBlock;
  std::vector<ColumnBlock> out(static_cast<size_t>(blocks));
  parallel_for(
      threads, blocks,
      [&](Index b0, Index b1) {
        std::vector<Index> mark(static_cast<size_t>(n), -1), mark_b(with_b ? static_cast<size_t>(n) : 0, -1);
        std::vector<Complex> acc(static_cast<size_t>(n)), acc_b(with_b ? static_cast<size_t>(n) : 0);
        std::vector<int> rows;
        for (Index b = b0; b < b1; ++b) {
          ColumnBlock& cb = out[static_cast<size_t>(b)];
          const Index j0 = b * kColumnBlock, j1 = std::min(n, j0 + kColumnBlock);
          cb.count.assign(static_cast<size_t>(j1 - j0), 0);
          for (Index j = j0; j < j1; ++j) {
            rows.clear();
            auto add = [&](const SpMatC& M, const RowMajor& R, std::vector<Index>& mk, std::vector<Complex>& ac) {
              for (SpMatC::InnerIterator it(M, j); it; ++it) {
                const Complex a = it.value();
                const size_t r = static_cast<size_t>(it.row());
                for (int q = R.start[r]; q < R.start[r + 1]; ++q) {
                  const size_t kk = static_cast<size_t>(R.col[static_cast<size_t>(q)]);
                  const Complex term = std::conj(R.val[static_cast<size_t>(q)]) * a;
                  const bool new_row = mark[kk] != j;  // B's rows may be new to column j too
                  if (mk[kk] != j) {
                    mk[kk] = j;
                    ac[kk] = term;
                  } else {
                    ac[kk] += term;
                  }
                  if (new_row) {
                    mark[kk] = j;
                    if (&ac != &acc) acc[kk] = Complex(0, 0);
                    rows.push_back(static_cast<int>(kk));
                  }
                }
              }
            };
            add(A, ar, mark, acc);
            if (with_b) add(*B, br, mark_b, acc_b);
            std::sort(rows.begin(), rows.end());
            cb.count[static_cast<size_t>(j - j0)] = static_cast<int>(rows.size());
            for (int kk : rows) {
              cb.row.push_back(kk);
              cb.val.push_back(with_b && mark_b[static_cast<size_t>(kk)] == j ? acc[static_cast<size_t>(kk)] + acc_b[static_cast<size_t>(kk)]
                                                                             : acc[static_cast<size_t>(kk)]);
            }
          }
        }
      },
      1);
  SpMatC K(n, n);
  std::vector<size_t> offset(static_cast<size_t>(blocks) + 1, 0);
  for (Index b = 0; b < blocks; ++b) offset[static_cast<size_t>(b) + 1] = offset[static_cast<size_t>(b)] + out[static_cast<size_t>(b)].row.size();
  K.resizeNonZeros(static_cast<Index>(offset.back()));
  int* outer = K.outerIndexPtr();
  outer[0] = 0;
  for (Index b = 0; b < blocks; ++b) {
    const ColumnBlock& cb = out[static_cast<size_t>(b)];
    for (size_t i = 0; i < cb.count.size(); ++i) {
      const Index j = b * kColumnBlock + static_cast<Index>(i);
      outer[j + 1] = outer[j] + cb.count[i];
    }
  }
  parallel_for(
      threads, blocks,
      [&](Index b0, Index b1) {
        for (Index b = b0; b < b1; ++b) {
          ColumnBlock& cb = out[static_cast<size_t>(b)];
          std::copy(cb.row.begin(), cb.row.end(), K.innerIndexPtr() + offset[static_cast<size_t>(b)]);
          std::copy(cb.val.begin(), cb.val.end(), K.valuePtr() + offset[static_cast<size_t>(b)]);
          cb = ColumnBlock{};
        }
      },
      1);
  return K;
}

SpMatC assemble_energy(const Topology& tp, const Coefficients& c, const std::vector<Complex>& sigma, double k, Residual form,
                       const SpMatC* B, int threads) {
  if (form == Residual::PerHalfEdge)
    return EnergyAssembler(tp, B, threads).assemble(compute_weights(tp, c, k, threads), sigma, threads);
  return assemble_energy(assemble_surface_operator(tp, c, sigma, k, form, threads), B, threads);
}

double energy_value(const SpMatC& A, const SpMatC* B, const VectorXc& z) {
  double e = (A * z).squaredNorm();
  if (B && B->rows()) e += ((*B) * z).squaredNorm();
  return e;
}

}  // namespace wefm
