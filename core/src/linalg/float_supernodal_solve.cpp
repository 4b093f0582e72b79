#include "wefm/core/linalg/float_supernodal_solve.hpp"
#include "wefm/core/sys/parallel.hpp"
#include "wefm/core/linalg/supernodal_split.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <cstdint>
#include <functional>
#include <limits>
#ifdef __linux__
#include <sys/mman.h>
#include <unistd.h>
#endif

#if (defined(__x86_64__) || defined(__i386__)) && (defined(__GNUC__) || defined(__clang__))
#define WEFM_FLOAT_FACTOR_X86 1
#include <immintrin.h>
#endif

namespace wefm {

namespace {

constexpr Index kPassBlocks = 8;  // blocks of the residual's maximum

std::atomic<int> g_kernels{static_cast<int>(FloatFactorKernels::Auto)};
std::atomic<std::size_t> g_min_entries{kFloatFactorMinEntries};

bool cpu_has_avx2_fma() {
#ifdef WEFM_FLOAT_FACTOR_X86
  static const bool has = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  }();
  return has;
#else
  return false;
#endif
}

bool disabled_by_environment() {
  static const bool off = [] {
    const char* v = std::getenv("WEFM_FLOAT_FACTOR");
    return v && std::strcmp(v, "0") == 0;
  }();
  return off;
}

}  // namespace

void set_float_factor_kernels(FloatFactorKernels k) { g_kernels.store(static_cast<int>(k)); }
void set_float_factor_min_entries(std::size_t entries) { g_min_entries.store(entries); }
std::size_t float_factor_min_entries() { return g_min_entries.load(); }

bool float_factor_kernels_available() {
  return g_kernels.load() == static_cast<int>(FloatFactorKernels::Auto) && !disabled_by_environment() && cpu_has_avx2_fma();
}

#ifdef WEFM_FLOAT_FACTOR_X86
namespace {

#define WEFM_AVX2 __attribute__((target("avx2,fma")))

// Lanes 0 .. 2 m - 1 of a vector of 4 complex floats (m < 4): the tail of a column.
WEFM_AVX2 inline __m256i tail_mask(int m) {
  return _mm256_cmpgt_epi32(_mm256_set1_epi32(2 * m), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
}

// w[0 .. m) -= l[0 .. m) * y, complex, (re, im) interleaved. With l = (lr, li): the real lane
// gets wr - lr yr + li yi, the imaginary lane wi - li yr - lr yi: one FMA with yr and one with the
// swapped pair (li, lr) times (yi, -yi).
WEFM_AVX2 inline void sub_scaled(float* w, const float* l, int m, float yr, float yi) {
  const __m256 vr = _mm256_set1_ps(yr);
  const __m256 vi = _mm256_setr_ps(yi, -yi, yi, -yi, yi, -yi, yi, -yi);
  int k = 0;
  for (; k + 8 <= m; k += 8) {
    const __m256 l0 = _mm256_loadu_ps(l + 2 * k), l1 = _mm256_loadu_ps(l + 2 * k + 8);
    __m256 w0 = _mm256_loadu_ps(w + 2 * k), w1 = _mm256_loadu_ps(w + 2 * k + 8);
    w0 = _mm256_fnmadd_ps(l0, vr, w0);
    w1 = _mm256_fnmadd_ps(l1, vr, w1);
    w0 = _mm256_fmadd_ps(_mm256_permute_ps(l0, 0xB1), vi, w0);
    w1 = _mm256_fmadd_ps(_mm256_permute_ps(l1, 0xB1), vi, w1);
    _mm256_storeu_ps(w + 2 * k, w0);
    _mm256_storeu_ps(w + 2 * k + 8, w1);
  }
  for (; k + 4 <= m; k += 4) {
    const __m256 l0 = _mm256_loadu_ps(l + 2 * k);
    __m256 w0 = _mm256_loadu_ps(w + 2 * k);
    w0 = _mm256_fnmadd_ps(l0, vr, w0);
    w0 = _mm256_fmadd_ps(_mm256_permute_ps(l0, 0xB1), vi, w0);
    _mm256_storeu_ps(w + 2 * k, w0);
  }
  if (k < m) {
    const __m256i mask = tail_mask(m - k);
    const __m256 l0 = _mm256_maskload_ps(l + 2 * k, mask);
    __m256 w0 = _mm256_maskload_ps(w + 2 * k, mask);
    w0 = _mm256_fnmadd_ps(l0, vr, w0);
    w0 = _mm256_fmadd_ps(_mm256_permute_ps(l0, 0xB1), vi, w0);
    _mm256_maskstore_ps(w + 2 * k, mask, w0);
  }
}

WEFM_AVX2 inline float horizontal_sum(__m256 v) {
  const __m128 h = _mm_add_ps(_mm256_castps256_ps128(v), _mm256_extractf128_ps(v, 1));
  const __m128 q = _mm_add_ps(h, _mm_movehl_ps(h, h));
  return _mm_cvtss_f32(_mm_add_ss(q, _mm_shuffle_ps(q, q, 1)));
}

// sum conj(l[i]) w[i] over i < m. Re = sum lr wr + li wi (the lanes of l * w); Im = sum lr wi - li wr
// (the lanes of l * swapped w, real lanes minus imaginary lanes). The entries are taken from the
// end down: the backward solve then reads the whole factor as one descending stream (columns and
// supernodes are visited from the top down), which the prefetcher follows; read upward, every
// column would start a new stream (docs/PERFORMANCE.md, "Measurements behind design choices").
WEFM_AVX2 inline void dot_conj(const float* l, const float* w, int m, float& re, float& im) {
  __m256 a0 = _mm256_setzero_ps(), b0 = _mm256_setzero_ps(), a1 = _mm256_setzero_ps(), b1 = _mm256_setzero_ps();
  int k = m;
  for (; k >= 8; k -= 8) {
    const __m256 l1 = _mm256_loadu_ps(l + 2 * k - 8), l0 = _mm256_loadu_ps(l + 2 * k - 16);
    const __m256 w1 = _mm256_loadu_ps(w + 2 * k - 8), w0 = _mm256_loadu_ps(w + 2 * k - 16);
    a1 = _mm256_fmadd_ps(l1, w1, a1);
    a0 = _mm256_fmadd_ps(l0, w0, a0);
    b1 = _mm256_fmadd_ps(l1, _mm256_permute_ps(w1, 0xB1), b1);
    b0 = _mm256_fmadd_ps(l0, _mm256_permute_ps(w0, 0xB1), b0);
  }
  if (k >= 4) {
    k -= 4;
    const __m256 l0 = _mm256_loadu_ps(l + 2 * k), w0 = _mm256_loadu_ps(w + 2 * k);
    a0 = _mm256_fmadd_ps(l0, w0, a0);
    b0 = _mm256_fmadd_ps(l0, _mm256_permute_ps(w0, 0xB1), b0);
  }
  if (k > 0) {
    const __m256i mask = tail_mask(k);
    const __m256 l0 = _mm256_maskload_ps(l, mask), w0 = _mm256_maskload_ps(w, mask);
    a1 = _mm256_fmadd_ps(l0, w0, a1);
    b1 = _mm256_fmadd_ps(l0, _mm256_permute_ps(w0, 0xB1), b1);
  }
  const __m256 sign = _mm256_setr_ps(1, -1, 1, -1, 1, -1, 1, -1);
  re = horizontal_sum(_mm256_add_ps(a0, a1));
  im = horizontal_sum(_mm256_mul_ps(_mm256_add_ps(b0, b1), sign));
}

// A supernode's rows of x into g: its own columns (contiguous from k1) first, then the rest.
inline void gather(const float* x, const int* rows, int k1, int nc, int nr, float* g) {
  std::memcpy(g, x + 2 * k1, sizeof(float) * 2 * static_cast<size_t>(nc));
  for (int i = nc; i < nr; ++i) {
    g[2 * i] = x[2 * rows[i]];
    g[2 * i + 1] = x[2 * rows[i] + 1];
  }
}

// The forward step of supernode sn (L y = b, in place on x). The diagonal entry of each column
// holds 1 / L_jj (see assign). The supernode's rows are gathered into g (its own columns first,
// contiguous in x), its columns applied there, and scattered back. With `owner`, rows owned by
// another part than `part` (the ancestors above a subtree part) are read from and written to
// `away` instead of x: two parts that share ancestors then never write the same element.
WEFM_AVX2 void forward_supernode(const SupernodalView& f, const float* values, int sn, float* x, float* g, const std::uint8_t* owner,
                                 std::uint8_t part, float* away) {
  const int k1 = f.super[sn], nc = f.super[sn + 1] - k1, nr = f.pi[sn + 1] - f.pi[sn];
  const int* rows = f.s + f.pi[sn];
  const float* L = values + 2 * static_cast<size_t>(f.px[sn]);
  std::memcpy(g, x + 2 * k1, sizeof(float) * 2 * static_cast<size_t>(nc));
  for (int i = nc; i < nr; ++i) {
    const float* src = owner && owner[rows[i]] != part ? away : x;
    g[2 * i] = src[2 * rows[i]];
    g[2 * i + 1] = src[2 * rows[i] + 1];
  }
  for (int j = 0; j < nc; ++j) {
    const float* col = L + 2 * (static_cast<size_t>(j) * nr + j);
    const float yr = g[2 * j] * col[0], yi = g[2 * j + 1] * col[0];
    g[2 * j] = yr;
    g[2 * j + 1] = yi;
    sub_scaled(g + 2 * (j + 1), col + 2, nr - j - 1, yr, yi);
  }
  std::memcpy(x + 2 * k1, g, sizeof(float) * 2 * static_cast<size_t>(nc));
  for (int i = nc; i < nr; ++i) {
    float* dst = owner && owner[rows[i]] != part ? away : x;
    dst[2 * rows[i]] = g[2 * i];
    dst[2 * rows[i] + 1] = g[2 * i + 1];
  }
}

// The backward step of supernode sn (L^H x = y): reads its rows (its ancestors' are final), writes
// only its own columns.
WEFM_AVX2 void backward_supernode(const SupernodalView& f, const float* values, int sn, float* x, float* g) {
  const int k1 = f.super[sn], nc = f.super[sn + 1] - k1, nr = f.pi[sn + 1] - f.pi[sn];
  const int* rows = f.s + f.pi[sn];
  const float* L = values + 2 * static_cast<size_t>(f.px[sn]);
  gather(x, rows, k1, nc, nr, g);
  for (int j = nc - 1; j >= 0; --j) {
    const float* col = L + 2 * (static_cast<size_t>(j) * nr + j);
    float re, im;
    dot_conj(col + 2, g + 2 * (j + 1), nr - j - 1, re, im);
    g[2 * j] = (g[2 * j] - re) * col[0];
    g[2 * j + 1] = (g[2 * j + 1] - im) * col[0];
  }
  std::memcpy(x + 2 * k1, g, sizeof(float) * 2 * static_cast<size_t>(nc));
}

#undef WEFM_AVX2

}  // namespace
#endif  // WEFM_FLOAT_FACTOR_X86

bool FloatSupernodalFactor::convert_in_place(const SupernodalView& f, const SupernodalSplit* split) {
  clear();
  if (!float_factor_kernels_available() || f.n <= 0 || f.nsuper <= 0 || !f.x) return false;
  // Each supernode's first rows must be its own columns (CHOLMOD's layout): the solves rely on it.
  int max_rows = 0;
  for (int sn = 0; sn < f.nsuper; ++sn) {
    const int k1 = f.super[sn], nc = f.super[sn + 1] - k1, nr = f.pi[sn + 1] - f.pi[sn];
    if (nc <= 0 || nr < nc) return false;
    for (int i = 0; i < nc; ++i)
      if (f.s[f.pi[sn] + i] != k1 + i) return false;
    max_rows = std::max(max_rows, nr);
  }
  // The range check, before anything is written (on failure the double factor stays as it was):
  // an entry above 2^60, or a diagonal outside [2^-60, 2^60], would overflow or lose the factor in
  // float (whose range is 2^+-126) once a residual of any size, scaled to 1, meets it.
  constexpr double kBig = 1152921504606846976.0;  // 2^60
  bool out_of_range = false;  // no early exit: the loop vectorises
  for (std::size_t k = 0; k < 2 * f.xsize; ++k) out_of_range |= !(std::abs(f.x[k]) <= kBig);
  if (out_of_range) return false;
  auto diagonal = [&](int sn, int j) {
    const int nr = f.pi[sn + 1] - f.pi[sn];
    return 2 * (static_cast<std::size_t>(f.px[sn]) + static_cast<std::size_t>(j) * nr + j);
  };
  for (int sn = 0; sn < f.nsuper; ++sn)
    for (int j = 0; j < f.super[sn + 1] - f.super[sn]; ++j) {
      const double d = f.x[diagonal(sn, j)];
      if (!(d >= 1.0 / kBig && d <= kBig)) return false;
    }
  // The diagonal is real and positive and only ever divided by: it is kept as its reciprocal
  // (computed in double, then rounded).
  for (int sn = 0; sn < f.nsuper; ++sn)
    for (int j = 0; j < f.super[sn + 1] - f.super[sn]; ++j) f.x[diagonal(sn, j)] = 1.0 / f.x[diagonal(sn, j)];
  // Entry k moves from bytes [16k, 16k + 16) to [8k, 8k + 8), which only ever lie over entries
  // already read; blocks go through a buffer by memcpy (no aliasing of double and float storage).
  constexpr std::size_t kBlock = 1024;
  double in[2 * kBlock];
  float out[2 * kBlock];
  unsigned char* bytes = reinterpret_cast<unsigned char*>(f.x);
  for (std::size_t k0 = 0; k0 < f.xsize; k0 += kBlock) {
    const std::size_t m = std::min(kBlock, f.xsize - k0);
    std::memcpy(in, bytes + 16 * k0, 16 * m);
    for (std::size_t i = 0; i < 2 * m; ++i) out[i] = static_cast<float>(in[i]);
    std::memcpy(bytes + 8 * k0, out, 8 * m);
  }
  f_ = f;
  values_ = reinterpret_cast<const float*>(f.x);
  max_rows_ = max_rows;
  plan_parts(split ? *split : split_supernodal_tree(f_));
  return true;
}

void FloatSupernodalFactor::release_unused() const {
#ifdef __linux__
  if (!values_) return;
  const std::uintptr_t page = static_cast<std::uintptr_t>(sysconf(_SC_PAGESIZE));
  const std::uintptr_t lo = reinterpret_cast<std::uintptr_t>(f_.x) + 8 * f_.xsize, hi = lo + 8 * f_.xsize;
  const std::uintptr_t a = (lo + page - 1) / page * page, b = hi / page * page;  // whole pages inside
  if (b > a) madvise(reinterpret_cast<void*>(a), b - a, MADV_DONTNEED);
#endif
}

void FloatSupernodalFactor::clear() {
  values_ = nullptr;
  std::vector<std::complex<float>>().swap(work_);
  for (auto& g : gather_) std::vector<std::complex<float>>().swap(g);
  for (auto& a : away_) std::vector<std::complex<float>>().swap(a);
  std::vector<std::uint8_t>().swap(owner_);
  for (auto& p : part_super_) std::vector<int>().swap(p);
  std::vector<int>().swap(rest_super_);
  std::vector<int>().swap(rest_cols_);
  f_ = SupernodalView();
  max_rows_ = 0;
}

void FloatSupernodalFactor::plan_parts(const SupernodalSplit& sp) {
  owner_.clear();
  for (auto& p : part_super_) p.clear();
  rest_super_.clear();
  rest_cols_.clear();
  if (sp.empty()) return;
  owner_.assign(static_cast<size_t>(f_.n), 0);
  for (int sn = 0; sn < f_.nsuper; ++sn)
    for (int c = f_.super[sn]; c < f_.super[sn + 1]; ++c) {
      owner_[static_cast<size_t>(c)] = sp.owner[static_cast<size_t>(sn)];
      if (sp.owner[static_cast<size_t>(sn)] == 0) rest_cols_.push_back(c);
    }
  part_super_[0] = sp.group[0];
  part_super_[1] = sp.group[1];
  rest_super_ = sp.rest;
}

void FloatSupernodalFactor::solve(const std::complex<double>* b, std::complex<double>* x, int cols) const {
#ifdef WEFM_FLOAT_FACTOR_X86
  const int n = f_.n;
  work_.resize(static_cast<size_t>(n));
  for (auto& g : gather_) g.resize(static_cast<size_t>(max_rows_));
  const bool split = !owner_.empty();
  if (split)
    for (auto& a : away_) a.resize(static_cast<size_t>(n));
  float* w = reinterpret_cast<float*>(work_.data());
  auto run_parts = [&](const std::function<void(int)>& part) {
    parallel_for(threads_, 2, [&](Index p0, Index p1) {
      for (Index p = p0; p < p1; ++p) part(static_cast<int>(p));
    }, 1);
  };
  for (int c = 0; c < cols; ++c) {
    const std::complex<double>* bc = b + static_cast<size_t>(c) * n;
    std::complex<double>* xc = x + static_cast<size_t>(c) * n;
    // A maximum, and element-by-element conversions: the same bits split over threads.
    double part_big[kPassBlocks] = {};
    parallel_for(threads_, kPassBlocks, [&](Index b0, Index b1) {
      for (Index blk = b0; blk < b1; ++blk) {
        double m = 0;
        for (int k = static_cast<int>(n * blk / kPassBlocks); k < static_cast<int>(n * (blk + 1) / kPassBlocks); ++k)
          m = std::max(m, std::max(std::abs(bc[k].real()), std::abs(bc[k].imag())));
        part_big[blk] = m;
      }
    }, 1);
    double big = 0;
    for (double m : part_big) big = std::max(big, m);
    // An infinite entry gives NaN, as in double (NaN entries go through the kernels as NaN); zero, zero.
    if (!std::isfinite(big) || big == 0) {
      std::fill(xc, xc + n, big == 0 ? std::complex<double>(0, 0) : std::complex<double>(std::numeric_limits<double>::quiet_NaN(), 0));
      continue;
    }
    int e = 0;
    std::frexp(big, &e);
    const double scale = std::ldexp(1.0, -e), unscale = std::ldexp(1.0, e);  // powers of two: exact
    parallel_for(threads_, n, [&](Index k0, Index k1) {
      for (Index k = k0; k < k1; ++k) {
        const std::complex<double> v = bc[f_.perm[k]] * scale;
        work_[static_cast<size_t>(k)] = std::complex<float>(static_cast<float>(v.real()), static_cast<float>(v.imag()));
      }
    });
    float* g0 = reinterpret_cast<float*>(gather_[0].data());
    if (!split) {
      for (int sn = 0; sn < f_.nsuper; ++sn) forward_supernode(f_, values_, sn, w, g0, nullptr, 0, nullptr);
      for (int sn = f_.nsuper - 1; sn >= 0; --sn) backward_supernode(f_, values_, sn, w, g0);
    } else {
      // Each part's updates of the rest's columns go to its own buffer, added in a fixed order.
      for (auto& a : away_)
        for (int k : rest_cols_) a[static_cast<size_t>(k)] = std::complex<float>(0, 0);
      run_parts([&](int p) {
        float* g = reinterpret_cast<float*>(gather_[static_cast<size_t>(p)].data());
        float* away = reinterpret_cast<float*>(away_[static_cast<size_t>(p)].data());
        for (int sn : part_super_[p]) forward_supernode(f_, values_, sn, w, g, owner_.data(), static_cast<std::uint8_t>(p + 1), away);
      });
      for (int k : rest_cols_) work_[static_cast<size_t>(k)] = (work_[static_cast<size_t>(k)] + away_[0][static_cast<size_t>(k)]) + away_[1][static_cast<size_t>(k)];
      for (int sn : rest_super_) forward_supernode(f_, values_, sn, w, g0, nullptr, 0, nullptr);
      for (auto it = rest_super_.rbegin(); it != rest_super_.rend(); ++it) backward_supernode(f_, values_, *it, w, g0);
      run_parts([&](int p) {
        float* g = reinterpret_cast<float*>(gather_[static_cast<size_t>(p)].data());
        for (auto it = part_super_[p].rbegin(); it != part_super_[p].rend(); ++it) backward_supernode(f_, values_, *it, w, g);
      });
    }
    parallel_for(threads_, n, [&](Index k0, Index k1) {
      for (Index k = k0; k < k1; ++k) {
        const std::complex<float> v = work_[static_cast<size_t>(k)];
        xc[f_.perm[k]] = std::complex<double>(v.real(), v.imag()) * unscale;
      }
    });
  }
#else
  (void)b;
  (void)x;
  (void)cols;  // convert_in_place() never succeeds without the kernels
#endif
}

}  // namespace wefm
