#include "laplacian_floor.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "process_stats.hpp"

#ifdef WEFM_BENCH_HAVE_CHOLMOD
#include <cholmod.h>
#endif

namespace wefm_bench {

#ifndef WEFM_BENCH_HAVE_CHOLMOD

bool floor_available() { return false; }
FloorResult measure_floor(const Face&, bool) {
  FloorResult r;
  r.error = "built without CHOLMOD";
  return r;
}

#else

bool floor_available() { return true; }

namespace {

const char* ordering_name(int ordering) {
  switch (ordering) {
    case CHOLMOD_NATURAL: return "natural";
    case CHOLMOD_GIVEN: return "given";
    case CHOLMOD_AMD: return "AMD";
    case CHOLMOD_METIS: return "METIS";
    case CHOLMOD_NESDIS: return "NESDIS";
    case CHOLMOD_COLAMD: return "COLAMD";
    case CHOLMOD_POSTORDERED: return "postordered";
    default: return "unknown";
  }
}

// Half the cotangents of the two angles facing each edge, accumulated per triangle corner.
struct Entry {
  int32_t row, col;
  double value;
};

std::vector<Entry> cotangent_entries(const Face& f) {
  std::vector<Entry> e;
  e.reserve(static_cast<size_t>(9 * f.triangles()));
  auto p = [&](int32_t v, int k) { return f.xyz[3 * static_cast<size_t>(v) + static_cast<size_t>(k)]; };
  for (int64_t t = 0; t < f.triangles(); ++t) {
    const int32_t* c = &f.tri[static_cast<size_t>(3 * t)];
    for (int j = 0; j < 3; ++j) {
      const int32_t a = c[j], b = c[(j + 1) % 3], o = c[(j + 2) % 3];
      double u[3], w[3];
      for (int k = 0; k < 3; ++k) {
        u[k] = p(a, k) - p(o, k);
        w[k] = p(b, k) - p(o, k);
      }
      const double dot = u[0] * w[0] + u[1] * w[1] + u[2] * w[2];
      const double cx = u[1] * w[2] - u[2] * w[1], cy = u[2] * w[0] - u[0] * w[2], cz = u[0] * w[1] - u[1] * w[0];
      const double cross = std::sqrt(cx * cx + cy * cy + cz * cz);
      const double half_cot = cross > 0 ? 0.5 * dot / cross : 0.0;
      // Vertex 0 is pinned: its row and column leave the system, the rest shift down by one.
      const int32_t ia = a - 1, ib = b - 1;
      if (ia >= 0) e.push_back({ia, ia, half_cot});
      if (ib >= 0) e.push_back({ib, ib, half_cot});
      if (ia >= 0 && ib >= 0) e.push_back({std::max(ia, ib), std::min(ia, ib), -half_cot});
    }
  }
  return e;
}

}  // namespace

FloorResult measure_floor(const Face& face, bool complex_arithmetic) {
  FloorResult r;
  const int64_t n = face.vertices() - 1;
  r.n = n;
  cholmod_common cm;
  cholmod_start(&cm);
  // Supernodal, as wefm's own factorisation (Eigen's CholmodSupernodalLLT); default orderings.
  cm.supernodal = CHOLMOD_SUPERNODAL;
  const double t0 = now_seconds();
  const std::vector<Entry> entries = cotangent_entries(face);
  const int xtype = complex_arithmetic ? CHOLMOD_COMPLEX : CHOLMOD_REAL;
  cholmod_triplet* T = cholmod_allocate_triplet(static_cast<size_t>(n), static_cast<size_t>(n), entries.size(), -1, xtype, &cm);
  auto* ti = static_cast<int*>(T->i);
  auto* tj = static_cast<int*>(T->j);
  auto* tx = static_cast<double*>(T->x);
  for (size_t k = 0; k < entries.size(); ++k) {
    ti[k] = entries[k].row;
    tj[k] = entries[k].col;
    if (complex_arithmetic) {
      tx[2 * k] = entries[k].value;
      tx[2 * k + 1] = 0.0;
    } else {
      tx[k] = entries[k].value;
    }
  }
  T->nnz = entries.size();
  cholmod_sparse* A = cholmod_triplet_to_sparse(T, 0, &cm);  // sums the duplicates
  cholmod_free_triplet(&T, &cm);
  const double t1 = now_seconds();
  r.assembly = t1 - t0;
  r.matrix_nnz = static_cast<int64_t>(cholmod_nnz(A, &cm));
  const double c1 = cpu_seconds();
  cholmod_factor* L = cholmod_analyze(A, &cm);
  const double t2 = now_seconds();
  r.analysis = t2 - t1;
  r.ordering = ordering_name(cm.method[cm.selected].ordering);
  cholmod_factorize(A, L, &cm);
  const double t3 = now_seconds();
  r.factorization = t3 - t2;
  if (cm.status != CHOLMOD_OK || L->minor < L->n) {
    r.error = "the cotangent Laplacian is not positive definite (CHOLMOD status " + std::to_string(cm.status) + ")";
  } else {
    cholmod_dense* b = cholmod_ones(static_cast<size_t>(n), 1, xtype, &cm);
    cholmod_dense* x = cholmod_solve(CHOLMOD_A, L, b, &cm);
    r.solve = now_seconds() - t3;
    r.cpu = cpu_seconds() - c1;
    r.ok = x != nullptr;
    if (!r.ok) r.error = "CHOLMOD solve failed";
    cholmod_free_dense(&x, &cm);
    cholmod_free_dense(&b, &cm);
  }
  r.factor_nnz = cm.lnz;
  r.flops = cm.fl;
  cholmod_free_factor(&L, &cm);
  cholmod_free_sparse(&A, &cm);
  cholmod_finish(&cm);
  return r;
}

#endif

}  // namespace wefm_bench
