#include "wefm/core/linalg/sparse_cholesky.hpp"
#include "wefm/core/linalg/nested_dissection.hpp"
#include "wefm/core/linalg/ordering_choice.hpp"

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>
#include <dlfcn.h>

#include "wefm/core/sys/clock.hpp"
#include "wefm/core/sys/error.hpp"
#include "wefm/core/linalg/float_supernodal_solve.hpp"
#include "wefm/core/sys/huge_pages.hpp"
#include "wefm/core/linalg/supernodal_inverse.hpp"
#include "wefm/core/linalg/supernodal_refactor.hpp"
#ifdef WEFM_HAVE_CHOLMOD
#include <Eigen/CholmodSupport>
#endif

namespace wefm {

namespace {
using SetBlasThreads = void (*)(int);
SetBlasThreads blas_threads_setter() {
  static const SetBlasThreads set = reinterpret_cast<SetBlasThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"));
  return set;
}
std::atomic<int> g_solve_blas_threads{0};
}  // namespace

bool set_solve_blas_threads(int threads) {
  if (threads > 0 && !blas_threads_setter()) return false;
  g_solve_blas_threads.store(threads < 0 ? 0 : threads);
  return true;
}

int solve_blas_threads() { return g_solve_blas_threads.load(); }

void apply_solve_blas_threads() {
  const int threads = g_solve_blas_threads.load();
  if (threads > 0 && blas_threads_setter()) blas_threads_setter()(threads);
}

namespace {

#ifdef WEFM_HAVE_CHOLMOD
// OpenBLAS takes a work buffer of 128 MB and a page for each thread that calls it, and where that
// allocation fails it retries without end instead of returning (0.3.21, Debian 12): under an
// address-space limit (`ulimit -v`) or strict overcommit the solve would hang inside BLAS. The same
// allocations are tried here first, untouched and given back at once, and their failure is out of
// memory. It keeps the buffers once it has them, so a thread count already probed is not again.
constexpr std::size_t kBlasBuffer = (std::size_t{128} << 20) + 4096;
std::atomic<int> g_blas_threads_probed{0};

void require_blas_workspace(int threads) {
  if (threads <= g_blas_threads_probed.load()) return;
  std::vector<void*> held;
  held.reserve(static_cast<std::size_t>(threads));
  for (int k = 0; k < threads; ++k) {
    void* p = std::malloc(kBlasBuffer);
    if (!p) break;
    held.push_back(p);
  }
  const bool ok = static_cast<int>(held.size()) == threads;
  for (void* p : held) std::free(p);
  if (!ok)
    fail(Errc::out_of_memory, "out of memory: the BLAS library needs a 128 MB work buffer for each of " + std::to_string(threads) +
                                  " threads of the factorisation, and the process cannot allocate them (an address-space limit?)");
  int seen = g_blas_threads_probed.load();
  while (seen < threads && !g_blas_threads_probed.compare_exchange_weak(seen, threads)) {
  }
}
#endif

// OpenMP regions opened by the calling thread run on it alone while this lives: the
// max-active-levels ICV of the calling thread's data environment is set to 0 and restored
// (OpenMP 5: a per-thread setting, so other threads and later regions of the caller are
// untouched; libgomp 12 keeps it per thread, a thread's change seen by no other, which
// tests/capi/test_host_process.cpp checks). Through dlsym, as for OpenBLAS: a no-op when no
// OpenMP runtime is loaded.
class SerialOpenMP {
 public:
  SerialOpenMP() {
    using Get = int (*)();
    static const Get get = reinterpret_cast<Get>(dlsym(RTLD_DEFAULT, "omp_get_max_active_levels"));
    static const SetLevels set = reinterpret_cast<SetLevels>(dlsym(RTLD_DEFAULT, "omp_set_max_active_levels"));
    if (!get || !set) return;
    set_ = set;
    old_ = get();
    set_(0);
  }
  ~SerialOpenMP() {
    if (set_) set_(old_);
  }
  SerialOpenMP(const SerialOpenMP&) = delete;
  SerialOpenMP& operator=(const SerialOpenMP&) = delete;

 private:
  using SetLevels = void (*)(int);
  SetLevels set_ = nullptr;
  int old_ = 0;
};

}  // namespace

bool have_cholmod() {
#ifdef WEFM_HAVE_CHOLMOD
  return true;
#else
  return false;
#endif
}

#ifdef WEFM_HAVE_CHOLMOD
// Eigen's wrapper with its cholmod_factor in reach: keep_single_precision converts its values.
template <class Matrix>
class CholmodLLT : public Eigen::CholmodSupernodalLLT<Matrix, Eigen::Lower> {
 public:
  cholmod_factor* factor() const { return this->m_cholmodFactor; }
  // The factor's values were computed outside CHOLMOD (supernodal_refactor.hpp): solves may go on.
  void mark_factorized() {
    this->m_factorizationIsOk = true;
    this->m_info = Eigen::Success;
  }
  // Eigen's analyzePattern with CHOLMOD's methods as the caller set them and an optional order.
  void analyze_with(const Matrix& K, int* perm) {
    if (this->m_cholmodFactor) cholmod_free_factor(&this->m_cholmodFactor, &this->cholmod());
    cholmod_sparse A = Eigen::viewAsCholmod(K.template selfadjointView<Eigen::Lower>());
    this->m_cholmodFactor = cholmod_analyze_p(&A, perm, nullptr, 0, &this->cholmod());
    this->m_isInitialized = true;
    this->m_info = this->m_cholmodFactor ? Eigen::Success : Eigen::NumericalIssue;
    this->m_analysisIsOk = this->m_cholmodFactor != nullptr;
    this->m_factorizationIsOk = false;
  }
};

// The factor entries and flops of P K P^T (CHOLMOD's Common lnz and fl) for the order perm: its
// elimination tree and column counts only, a fraction of a symbolic analysis.
template <class Matrix>
static bool count_order(cholmod_common& c, const Matrix& K, std::vector<int>& perm) {
  cholmod_sparse A = Eigen::viewAsCholmod(K.template selfadjointView<Eigen::Lower>());
  const size_t n = static_cast<size_t>(K.rows());
  std::vector<int> parent(n), post(n), count(n), first(n), level(n);
  return cholmod_analyze_ordering(&A, CHOLMOD_GIVEN, perm.data(), nullptr, 0, parent.data(), post.data(), count.data(), first.data(),
                                  level.data(), &c) != 0;
}

// The ordering: AMD; when its fill is poor by CHOLMOD's test (the one after which CHOLMOD's default
// strategy runs METIS) or doubtful, a geometric nested dissection on `points`, kept when it is
// acceptable and, against a usable AMD order, needs fewer flops (counted before it is analysed);
// ordering_choice.hpp has the rule. When neither will do, or there are no points, CHOLMOD's
// default (AMD, then METIS). The AMD case gives CHOLMOD's default result.
template <class LLT, class Matrix>
static void analyze_ordered(LLT& llt, const Matrix& K, const std::vector<Vec3>& points) {
  cholmod_common& c = llt.cholmod();
  const double anz = 0.5 * static_cast<double>(K.nonZeros() + K.rows());
  const double n = static_cast<double>(K.rows());
  if (points.size() != static_cast<size_t>(K.rows())) {
    llt.analyzePattern(K);
    return;
  }
  const int saved_nmethods = c.nmethods, saved_ordering = c.method[0].ordering;
  c.nmethods = 1;
  c.method[0].ordering = CHOLMOD_AMD;
  llt.analyze_with(K, nullptr);
  const OrderCounts amd{c.lnz, c.fl};
  const bool amd_ok = llt.factor() && !poor_order(amd, anz);
  bool done = amd_ok && !doubtful_order(amd, anz);
  if (!done) {
    std::vector<int> perm = geometric_nested_dissection(K.outerIndexPtr(), K.innerIndexPtr(), points);
    // A poor AMD order goes whatever the dissection's counts, so the dissection is analysed straight
    // away and judged after; against a usable one it is counted first and analysed only if it wins.
    const bool analyse_dissection =
        !amd_ok || (count_order(c, K, perm) && dissection_acceptable({c.lnz, c.fl}, anz, n) && c.fl < amd.fl);
    if (analyse_dissection) {
      c.method[0].ordering = CHOLMOD_GIVEN;
      llt.analyze_with(K, perm.data());
      done = llt.factor() && (amd_ok || dissection_acceptable({c.lnz, c.fl}, anz, n));
    } else {
      // AMD's analysis is still the factor's (neither the dissection's symbolic analysis nor a
      // second one of AMD's is needed); its counts go back.
      c.lnz = amd.lnz;
      c.fl = amd.fl;
      done = true;
    }
  }
  c.nmethods = saved_nmethods;
  c.method[0].ordering = saved_ordering;
  if (!done) llt.analyzePattern(K);
}

// A complex supernodal LL^H factor with int indices and all its columns factorised, as a view.
static bool supernodal_view(cholmod_factor* L, SupernodalView& v) {
  if (!L || !L->is_super || !L->is_ll || L->xtype != CHOLMOD_COMPLEX || L->itype != CHOLMOD_INT || L->dtype != CHOLMOD_DOUBLE ||
      L->xsize > static_cast<size_t>(std::numeric_limits<int>::max()) || L->minor != L->n || !L->x)
    return false;
  v.n = static_cast<int>(L->n);
  v.nsuper = static_cast<int>(L->nsuper);
  v.super = static_cast<const int*>(L->super);
  v.pi = static_cast<const int*>(L->pi);
  v.px = static_cast<const int*>(L->px);
  v.s = static_cast<const int*>(L->s);
  v.perm = static_cast<const int*>(L->Perm);
  v.x = static_cast<double*>(L->x);
  v.xsize = L->xsize;
  return true;
}
#endif

namespace {
std::atomic<bool> g_own_refactor{true};
}  // namespace

void set_supernodal_refactor(bool on) { g_own_refactor.store(on); }

// Eigen's LDLT with its factor's pattern in reach: the analysis sizes it (memory_limit_mb).
template <class Matrix>
class EigenLDLT : public Eigen::SimplicialLDLT<Matrix, Eigen::Lower, Eigen::AMDOrdering<int>> {
 public:
  std::size_t factor_entries() const { return static_cast<std::size_t>(this->m_matrix.nonZeros() + this->m_matrix.rows()); }
};

template <class Scalar>
struct SparseCholeskyT<Scalar>::Impl {
  bool use_cholmod = false;
#ifdef WEFM_HAVE_CHOLMOD
  CholmodLLT<Matrix> cholmod;
#endif
  FloatSupernodalFactor single;  // when keep_single_precision() took the factor over
  SupernodalRefactor refactor;   // numeric factorisations without CHOLMOD's OpenMP (supernodal_refactor.hpp)
  bool numeric_done = false;     // this analysis has been factorised once
  EigenLDLT<Matrix> ldlt;

  explicit Impl(bool cholmod_wanted) : use_cholmod(cholmod_wanted) {
#ifdef WEFM_HAVE_CHOLMOD
    // CHOLMOD reports problems on stdout/stderr by default; the library reports them as statuses.
    cholmod.cholmod().print = 0;
    // Ordering: AMD; where its fill is poor (CHOLMOD's test) a geometric nested dissection when
    // the caller gave points (set_ordering_points); METIS (CHOLMOD's default fallback) when that is
    // poor too and beyond a planar graph's growth (ordering_choice.hpp). On a large disk the
    // boundary term's couplings along the loop make AMD's fill poor; METIS's analysis then costs
    // many times the nested dissection's for a factor of about the same size. On a plate AMD's fill
    // passes and is kept (docs/PERFORMANCE.md, "Measurements behind design choices"). Cheap
    // renumberings before AMD, METIS on a coarsened graph and METIS's own options were measured and
    // dropped (docs/PERFORMANCE.md).
#endif
  }
};

template <class Scalar>
SparseCholeskyT<Scalar>::SparseCholeskyT(Backend backend)
    : impl_(std::make_unique<Impl>(have_cholmod() && backend != Backend::Eigen)) {
  if (backend == Backend::Cholmod && !have_cholmod()) fail(Errc::unsupported, "this build of wefm has no CHOLMOD (built with WEFM_WITH_SUITESPARSE=OFF)");
}

template <class Scalar>
SparseCholeskyT<Scalar>::~SparseCholeskyT() = default;

template <class Scalar>
bool SparseCholeskyT<Scalar>::analyze(const Matrix& K) {
  const bool same = K.rows() == n_ && K.isCompressed() &&
                    pattern_outer_.size() == static_cast<size_t>(K.outerSize() + 1) &&
                    std::equal(pattern_outer_.begin(), pattern_outer_.end(), K.outerIndexPtr()) &&
                    std::equal(pattern_inner_.begin(), pattern_inner_.end(), K.innerIndexPtr());
  if (same) return false;
  const SerialOpenMP serial;
  impl_->single.clear();  // its values are CHOLMOD's, which a new analysis drops
  impl_->refactor.clear();
  impl_->numeric_done = false;
  const double t0 = now();
  n_ = static_cast<Index>(K.rows());
  pattern_outer_.assign(K.outerIndexPtr(), K.outerIndexPtr() + K.outerSize() + 1);
  pattern_inner_.assign(K.innerIndexPtr(), K.innerIndexPtr() + K.nonZeros());
#ifdef WEFM_HAVE_CHOLMOD
  if (impl_->use_cholmod) {
    analyze_ordered(impl_->cholmod, K, points_);
    std::vector<Vec3>().swap(points_);
  } else
#endif
    impl_->ldlt.analyzePattern(K);
  ++counters_.analyses;
  counters_.time_analysis += now() - t0;
  if (limit_mb_ > 0) {
    const double mb = other_mb_ + 1e-6 * static_cast<double>(sizeof(Scalar)) * static_cast<double>(factor_entries());
    if (mb > limit_mb_) {
      pattern_outer_.clear();  // analyse again next time: the limit may have been raised
      fail(Errc::out_of_memory, "the solve is estimated at " + std::to_string(static_cast<long long>(mb + 0.5)) +
                                    " MB (factor " + std::to_string(factor_entries()) + " entries), above memory_limit_mb " +
                                    std::to_string(static_cast<long long>(limit_mb_)));
    }
  }
  // The own factorisation's map of K's entries needs only the pattern: made here, so that an
  // analysis run ahead of the values (flatten's early analysis) takes it along.
  const double t1 = now();
  prepare_own_refactor(K);
  counters_.time_analysis += now() - t1;
  return true;
}

template <class Scalar>
void SparseCholeskyT<Scalar>::prepare_own_refactor(const Matrix& K) {
#ifdef WEFM_HAVE_CHOLMOD
  if constexpr (std::is_same_v<Scalar, Complex>) {
    if (!impl_->use_cholmod || !g_own_refactor.load() || impl_->refactor.ready()) return;
    cholmod_factor* L = impl_->cholmod.factor();
    if (!impl_->numeric_done && L && L->is_super && L->xtype == CHOLMOD_PATTERN) {
      // The symbolic factor's values laid out (and allocated, not yet touched) as CHOLMOD's own
      // numeric factorisation would, so that the first factorisation is the own one too.
      cholmod_change_factor(CHOLMOD_COMPLEX, 1, 1, 1, 1, L, &impl_->cholmod.cholmod());
    }
    SupernodalView v;
    if (supernodal_view(L, v)) impl_->refactor.prepare(v, K);
  }
#else
  (void)K;
#endif
}

template <class Scalar>
void SparseCholeskyT<Scalar>::factorize(const Matrix& K) {
  analyze(K);
  const SerialOpenMP serial;
  impl_->single.clear();  // its values are CHOLMOD's, which the factorisation overwrites
  const double t0 = now();
  Eigen::ComputationInfo info;
#ifdef WEFM_HAVE_CHOLMOD
  if (impl_->use_cholmod) {
    require_blas_workspace(std::max(1, threads_));
    // The numeric factorisation without CHOLMOD's OpenMP regions (supernodal_refactor.hpp), on
    // CHOLMOD's analysis; CHOLMOD's own where that cannot be used (switched off, or a factor of
    // another kind).
    bool own = false;
    if constexpr (std::is_same_v<Scalar, Complex>) {
      prepare_own_refactor(K);  // when switched on since the analysis
      own = g_own_refactor.load() && impl_->refactor.ready();
      if (own) {
        info = impl_->refactor.factorize(K, threads_) ? Eigen::Success : Eigen::NumericalIssue;
        if (info == Eigen::Success) impl_->cholmod.mark_factorized();
      }
    }
    if (!own) {
      impl_->cholmod.factorize(K);
      info = impl_->cholmod.info();
    }
    impl_->numeric_done = info == Eigen::Success;
  } else
#endif
  {
    impl_->ldlt.factorize(K);
    info = impl_->ldlt.info();
    // LDLT succeeds on indefinite matrices; positive definiteness is what the energy promises.
    if (info == Eigen::Success && (impl_->ldlt.vectorD().real().array() <= 0).any()) info = Eigen::NumericalIssue;
  }
  ++counters_.factorizations;
  counters_.time_factorization += now() - t0;
  if (info != Eigen::Success) {
    pattern_outer_.clear();  // force a fresh analysis next time
#ifdef WEFM_HAVE_CHOLMOD
    if (impl_->use_cholmod && impl_->cholmod.cholmod().status == CHOLMOD_OUT_OF_MEMORY)
      fail(Errc::out_of_memory, "out of memory in the sparse Cholesky factorisation");
#endif
    fail(Errc::not_positive_definite, "the energy matrix is not positive definite (a use with no valid prediction, or a face whose triangles are all degenerate)");
  }
}

template <class Scalar>
void SparseCholeskyT<Scalar>::release() {
  impl_ = std::make_unique<Impl>(impl_->use_cholmod);
  pattern_outer_.clear();
  pattern_inner_.clear();
  n_ = 0;
}

template <class Scalar>
std::size_t SparseCholeskyT<Scalar>::factor_entries() const {
#ifdef WEFM_HAVE_CHOLMOD
  if (impl_->use_cholmod) {
    const cholmod_factor* L = impl_->cholmod.factor();
    return L ? L->xsize : 0;
  }
#endif
  return impl_->ldlt.factor_entries();
}

template <class Scalar>
bool SparseCholeskyT<Scalar>::keep_single_precision() {
#ifdef WEFM_HAVE_CHOLMOD
  if constexpr (std::is_same_v<Scalar, Complex>) {
    if (!impl_->use_cholmod || !impl_->single.empty()) return !impl_->single.empty();
    SupernodalView v;
    if (!supernodal_view(impl_->cholmod.factor(), v) || v.xsize < float_factor_min_entries()) return false;
    const double t0 = now();
    if (!impl_->single.convert_in_place(v, impl_->refactor.ready() ? &impl_->refactor.split() : nullptr)) return false;
    // The converted factor stays in CHOLMOD's value array, which CHOLMOD still takes for a numeric
    // factor: solve() never hands it to CHOLMOD while the float factor is in use, and the next
    // factorize overwrites every entry (it clears each supernode before assembling it).
    // Its second half is given back to the system, which lowers the solve's peak memory
    // (docs/PERFORMANCE.md, "Measurements behind design choices").
    impl_->single.release_unused();
    counters_.time_factorization += now() - t0;
    return true;
  }
#endif
  return false;
}

template <class Scalar>
bool SparseCholeskyT<Scalar>::single_precision() const {
  return !impl_->single.empty();
}

template <class Scalar>
std::size_t SparseCholeskyT<Scalar>::single_precision_shared_columns() const {
  return impl_->single.shared_columns();
}

template <class Scalar>
typename SparseCholeskyT<Scalar>::Dense SparseCholeskyT<Scalar>::solve(const Dense& rhs) {
  const double t0 = now();
  Dense x;
  if (!impl_->single.empty()) {
    x.resize(rhs.rows(), rhs.cols());
    impl_->single.set_threads(threads_);
    impl_->single.solve(rhs.data(), x.data(), static_cast<int>(rhs.cols()));
    counters_.solves += rhs.cols();
    counters_.time_solve += now() - t0;
    return x;
  }
#ifdef WEFM_HAVE_CHOLMOD
  if (impl_->use_cholmod) {
    // Eigen's wrapper notes a failed cholmod_solve (its workspace could not be allocated) in
    // info() and leaves the result unset: it must not reach the caller as a layout.
    x = impl_->cholmod.solve(rhs);
    if (impl_->cholmod.info() != Eigen::Success) {
      if (impl_->cholmod.cholmod().status == CHOLMOD_OUT_OF_MEMORY) fail(Errc::out_of_memory, "out of memory in the sparse Cholesky solve");
      fail(Errc::internal, "the sparse Cholesky solve failed (CHOLMOD status " + std::to_string(impl_->cholmod.cholmod().status) + ")");
    }
  } else
#endif
    x = impl_->ldlt.solve(rhs);
  counters_.solves += rhs.cols();
  counters_.time_solve += now() - t0;
  return x;
}

template <class Scalar>
bool SparseCholeskyT<Scalar>::inverse_entries(const std::vector<Index>& rows, const std::vector<Index>& cols, std::size_t max_entries,
                                              Dense& out) {
#ifdef WEFM_HAVE_CHOLMOD
  if constexpr (std::is_same_v<Scalar, Complex>) {
    SupernodalView v;
    if (!impl_->use_cholmod || !impl_->numeric_done || !impl_->single.empty() || !supernodal_view(impl_->cholmod.factor(), v)) return false;
    const double t0 = now();
    if (!supernodal_inverse_entries(v, rows, cols, max_entries, threads_, out)) return false;
    counters_.solves += static_cast<std::int64_t>(cols.size());
    counters_.time_solve += now() - t0;
    return true;
  }
#endif
  (void)rows, (void)cols, (void)max_entries, (void)out;
  return false;
}

template class SparseCholeskyT<Complex>;

}  // namespace wefm
