#pragma once
// A supernodal Cholesky factor L (L L^H = P A P^T, in CHOLMOD's supernodal layout) converted to
// single precision (complex float) in place, with its own forward and backward triangular solves.
//
// Why: from s > 0 on, the continuation spends most of its time applying its preconditioner, a
// Cholesky factor of the s = 0 matrix refactorised with the Gauss-Newton values. Each application
// is two triangular solves, and a single-vector triangular solve reads the whole factor once per
// direction for a multiply-add per entry: it is bound by memory bandwidth, since a large face's
// factor (tens of millions of complex entries) fits in no cache. A
// preconditioner needs only a few digits (CG stops at 1e-2 in its norm, and the CG itself stays in
// double), so a float factor halves the bytes read per application and the factor's memory.
//
// The kernels are AVX2 + FMA, chosen at run time (`__builtin_cpu_supports`): a machine without them
// (or WEFM_FLOAT_FACTOR=0 in the environment, or set_float_factor_kernels(Fallback)) keeps the
// double factor and CHOLMOD's own solves. The solves split the elimination tree into two groups of
// disjoint subtrees and their common ancestors (plan_parts); with set_threads(2 or more) the two
// groups run at once. The split and every sum's order are fixed by the factor alone, so the result
// does not depend on the number of threads.
#include <complex>
#include <cstdint>
#include <cstddef>
#include <vector>

namespace wefm {

enum class FloatFactorKernels { Auto, Fallback };

// Process-wide switch for tests and A/B timings: Fallback makes every factor created afterwards
// keep the double path. Auto (the default) uses the float kernels where the CPU has them, unless
// the environment has WEFM_FLOAT_FACTOR=0.
void set_float_factor_kernels(FloatFactorKernels k);
// True when factors made now get the float kernels: the switch is Auto, WEFM_FLOAT_FACTOR is not
// 0 and the CPU has AVX2 and FMA.
bool float_factor_kernels_available();

// Factors with fewer complex entries keep the double path (SparseCholesky::keep_single_precision):
// a small factor is read from the caches, not from memory, so halving its bytes gains little, and
// the small faces' layouts stay those of the double preconditioner to the bit. The default, 2^20
// entries, is 16 MB in double. Supernodal entries (L->xsize, the full rectangle of each supernode)
// measured with wefm's continuation factor: the real CAD sample's largest faces (10k uses) 0.6M,
// the 100k-triangle benchmark faces 2.2M (plate) and 4.1M (disk), at 1M triangles 27M and 34M.
// Settable for tests (0: every supernodal factor).
constexpr std::size_t kFloatFactorMinEntries = std::size_t(1) << 20;
void set_float_factor_min_entries(std::size_t entries);
std::size_t float_factor_min_entries();

// A supernodal LL^H factor's arrays (CHOLMOD's int version: L->super, L->pi, L->px, L->s, L->Perm
// and the interleaved complex values L->x). The float factor keeps pointing at all of them: the
// integer arrays belong to the symbolic analysis, the values are converted in place, and the owner
// clears the float factor before it refactorises or analyses again.
struct SupernodalView {
  int n = 0;             // columns
  int nsuper = 0;        // supernodes
  const int* super = nullptr;  // nsuper + 1: first column of each supernode
  const int* pi = nullptr;     // nsuper + 1: start of each supernode's row indices in s
  const int* px = nullptr;     // nsuper + 1: start of each supernode's values (complex entries)
  const int* s = nullptr;      // row indices; each supernode's first rows are its own columns
  const int* perm = nullptr;   // n: row k of P A P^T is row perm[k] of A
  double* x = nullptr;         // values, (re, im) interleaved, column-major per supernode
  std::size_t xsize = 0;       // complex entries in x
};

struct SupernodalSplit;  // supernodal_split.hpp

class FloatSupernodalFactor {
 public:
  // Converts the values to single precision in place: the float factor occupies the first half of
  // x's bytes (no second buffer: a separate float copy would raise the solve's peak memory at the
  // conversion), and the second half is free to be released
  // (release_unused). The double values are gone afterwards: only a refactorisation
  // brings them back. Returns false and leaves x untouched when the kernels are not available or a
  // value would not survive the conversion (a diagonal entry outside [2^-60, 2^60], any entry
  // above 2^60, or not finite): the caller then keeps its double factor.
  // `split`: the tree's split when the caller has it for this analysis (SupernodalRefactor keeps
  // one); computed here otherwise.
  bool convert_in_place(const SupernodalView& f, const SupernodalSplit* split = nullptr);
  // Gives the pages of x's second half back to the system (Linux: madvise MADV_DONTNEED; they read
  // as zeros until written again, which a refactorisation does).
  void release_unused() const;
  void clear();
  bool empty() const { return values_ == nullptr; }

  // x = A^{-1} b for `cols` columns (column-major, leading dimension n). Each column is scaled by
  // a power of two to a largest entry of 1 before it is rounded to float (exact, and the
  // preconditioner stays homogeneous whatever the residual's size), solved, and scaled back.
  void solve(const std::complex<double>* b, std::complex<double>* x, int cols) const;
  // Threads for solve(): 1 (or less) runs everything on the calling thread, 2 or more runs the
  // two parts of the tree at once.
  void set_threads(int threads) { threads_ = threads; }
  // Columns in the part of the tree that waits for both groups (0 when the solve is not split).
  std::size_t shared_columns() const { return rest_cols_.size(); }

 private:
  void plan_parts(const SupernodalSplit& sp);
  SupernodalView f_;
  const float* values_ = nullptr;  // (re, im) interleaved over f_.x's first half
  int max_rows_ = 0;  // rows of the tallest supernode: the size of the gather buffer
  mutable std::vector<std::complex<float>> work_;
  mutable std::vector<std::complex<float>> gather_[2];  // per part (one each while they run at once)
  // The split: per column 1 or 2 (its part), 0 (the common ancestors); each part's supernodes and
  // the rest's, increasing; the rest's columns; each part's updates of those columns.
  std::vector<std::uint8_t> owner_;
  std::vector<int> part_super_[2], rest_super_, rest_cols_;
  mutable std::vector<std::complex<float>> away_[2];
  int threads_ = 1;
};

}  // namespace wefm
