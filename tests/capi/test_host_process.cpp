// A host program that uses OpenBLAS and CHOLMOD itself (wefm.h, "Process."). Mode `default`: the
// host sets OpenBLAS to 2 threads, its own SuiteSparse allocator and OpenMP max-active-levels 3,
// factorises with CHOLMOD on a thread of its own while wefm solves a face (on 1 and on 2 threads)
// on this one, and finds every process setting as it left it, its own CHOLMOD results right, and
// the layouts of both wefm thread counts bit-identical. Mode `opt-in`: each process policy does
// what wefm.h says, and bad keys and values are refused.
#include <atomic>
#include <cfenv>
#include <clocale>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include <cholmod.h>
#include <dlfcn.h>
#include <sys/resource.h>
#if defined(__x86_64__)
#include <xmmintrin.h>
#endif

#include <wefm/wefm.h>

extern char** environ;

namespace {

int failures = 0;

#define EXPECT(cond)                                                  \
  do {                                                                \
    if (!(cond)) {                                                    \
      std::fprintf(stderr, "%s:%d: failed: %s\n", __FILE__, __LINE__, #cond); \
      ++failures;                                                     \
    }                                                                 \
  } while (0)

// Through dlsym, as the library reaches them: OpenBLAS and libgomp come in with CHOLMOD.
template <class F>
F symbol(const char* name) {
  return reinterpret_cast<F>(dlsym(RTLD_DEFAULT, name));
}
const auto blas_set = symbol<void (*)(int)>("openblas_set_num_threads");
const auto blas_get = symbol<int (*)()>("openblas_get_num_threads");
const auto omp_get_levels = symbol<int (*)()>("omp_get_max_active_levels");
const auto omp_set_levels = symbol<void (*)(int)>("omp_set_max_active_levels");

// The host's SuiteSparse allocator: the C library's, counted.
std::atomic<long> host_allocations{0};
void* host_malloc(size_t n) {
  ++host_allocations;
  return std::malloc(n);
}
void* host_calloc(size_t n, size_t m) {
  ++host_allocations;
  return std::calloc(n, m);
}
void* host_realloc(void* p, size_t n) { return std::realloc(p, n); }
void host_free(void* p) { std::free(p); }

// What belongs to the whole process, as far as a host can read it back.
struct ProcessState {
  unsigned char suitesparse[sizeof SuiteSparse_config];
  int blas_threads = -1;
  std::vector<std::string> environment;
  std::string locale;
  int rounding = 0, traps = 0;
  unsigned csr_modes = 0;  // MXCSR's rounding, flush-to-zero and denormals-are-zero bits
  std::vector<void*> handlers;
  std::vector<rlim_t> limits;

  static ProcessState read() {
    ProcessState s;
    std::memcpy(s.suitesparse, &SuiteSparse_config, sizeof s.suitesparse);
    if (blas_get) s.blas_threads = blas_get();
    for (char** e = environ; *e; ++e) s.environment.emplace_back(*e);
    s.locale = std::setlocale(LC_ALL, nullptr);
    s.rounding = std::fegetround();
    s.traps = fegetexcept();
#if defined(__x86_64__)
    s.csr_modes = _mm_getcsr() & 0xFFC0u;
#endif
    for (int sig = 1; sig < NSIG; ++sig) {
      struct sigaction a {};
      sigaction(sig, nullptr, &a);
      s.handlers.push_back(reinterpret_cast<void*>(a.sa_handler));
    }
    for (int r : {RLIMIT_AS, RLIMIT_DATA, RLIMIT_STACK, RLIMIT_NOFILE, RLIMIT_CORE, RLIMIT_NPROC}) {
      rlimit l{};
      getrlimit(r, &l);
      s.limits.push_back(l.rlim_cur);
      s.limits.push_back(l.rlim_max);
    }
    return s;
  }
};

void expect_same(const ProcessState& a, const ProcessState& b) {
  EXPECT(std::memcmp(a.suitesparse, b.suitesparse, sizeof a.suitesparse) == 0);
  EXPECT(a.blas_threads == b.blas_threads);
  EXPECT(a.environment == b.environment);
  EXPECT(a.locale == b.locale);
  EXPECT(a.rounding == b.rounding);
  EXPECT(a.traps == b.traps);
  EXPECT(a.csr_modes == b.csr_modes);
  EXPECT(a.handlers == b.handlers);
  EXPECT(a.limits == b.limits);
}

// A doubly curved n x n grid patch (large enough for CHOLMOD's supernodes to reach threaded BLAS).
struct Face {
  std::vector<double> xyz;
  std::vector<int32_t> tri;
};
Face bumpy(int n) {
  Face f;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const double u = double(j) / n, v = double(i) / n;
      f.xyz.insert(f.xyz.end(), {u, v, 0.3 * std::sin(2.0 * u) * std::cos(3.0 * v)});
    }
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const int32_t a = i * (n + 1) + j, b = a + 1, c = a + n + 2, d = a + n + 1;
      f.tri.insert(f.tri.end(), {a, b, c, a, c, d});
    }
  return f;
}

// Solves f with CHOLMOD on `threads` threads at s = 1; the UVs, empty on failure.
std::vector<double> solve(const Face& f, int threads) {
  wefm_face* face = nullptr;
  wefm_options o;
  wefm_options_init(&o, sizeof o);
  o.solver = WEFM_SOLVER_CHOLMOD;
  o.threads = threads;
  int64_t count = 0;
  std::vector<double> uv;
  wefm_status st = wefm_face_create(&face);
  if (st == WEFM_OK) st = wefm_face_set_mesh(face, int64_t(f.xyz.size() / 3), f.xyz.data(), int64_t(f.tri.size() / 3), f.tri.data());
  if (st == WEFM_OK) st = wefm_face_set_options(face, &o);
  if (st == WEFM_OK) st = wefm_face_solve(face);
  if (st == WEFM_OK) st = wefm_face_get_uv(face, nullptr, 0, &count);
  if (st == WEFM_OK) {
    uv.resize(size_t(count));
    st = wefm_face_get_uv(face, uv.data(), count, &count);
  }
  if (st != WEFM_OK) {
    std::fprintf(stderr, "solve: %s: %s\n", wefm_status_string(st), wefm_face_last_error(face));
    uv.clear();
  }
  wefm_face_release(face);
  return uv;
}

// The host's own CHOLMOD work: supernodal factorisations of a 2D Laplacian plus identity, solved
// and checked, until `stop`; meanwhile this thread's OpenMP setting and the process's BLAS and
// SuiteSparse settings are watched for any change, even a passing one.
struct HostCholmod {
  std::atomic<bool> stop{false};
  int rounds = 0, wrong = 0, changed = 0;

  void run(const ProcessState& expected) {
    if (omp_set_levels) omp_set_levels(3);
    cholmod_common c;
    cholmod_start(&c);
    c.supernodal = CHOLMOD_SUPERNODAL;
    const int n = 70, N = n * n;
    cholmod_triplet* t = cholmod_allocate_triplet(N, N, 3 * N, -1, CHOLMOD_REAL, &c);
    auto add = [&](int i, int j, double v) {
      static_cast<int*>(t->i)[t->nnz] = i;
      static_cast<int*>(t->j)[t->nnz] = j;
      static_cast<double*>(t->x)[t->nnz++] = v;
    };
    for (int k = 0; k < N; ++k) {
      add(k, k, 5.0);
      if (k % n + 1 < n) add(k + 1, k, -1.0);
      if (k + n < N) add(k + n, k, -1.0);
    }
    cholmod_sparse* A = cholmod_triplet_to_sparse(t, 0, &c);
    cholmod_dense* b = cholmod_ones(N, 1, CHOLMOD_REAL, &c);
    do {
      cholmod_factor* L = cholmod_analyze(A, &c);
      cholmod_factorize(A, L, &c);
      cholmod_dense* x = cholmod_solve(CHOLMOD_A, L, b, &c);
      cholmod_dense* r = cholmod_copy_dense(b, &c);
      double one[2] = {1, 0}, minus[2] = {-1, 0};
      cholmod_sdmult(A, 0, minus, one, x, r, &c);  // r = b - A x
      if (!x || cholmod_norm_dense(r, 0, &c) > 1e-10) ++wrong;
      cholmod_free_dense(&r, &c);
      cholmod_free_dense(&x, &c);
      cholmod_free_factor(&L, &c);
      if (omp_get_levels && omp_get_levels() != 3) ++changed;
      if (std::memcmp(&SuiteSparse_config, expected.suitesparse, sizeof expected.suitesparse) != 0) ++changed;
      if (blas_get && blas_get() != expected.blas_threads) ++changed;
      ++rounds;
    } while (!stop.load());
    cholmod_free_dense(&b, &c);
    cholmod_free_sparse(&A, &c);
    cholmod_free_triplet(&t, &c);
    cholmod_finish(&c);
  }
};

int run_default() {
  if (blas_set) blas_set(2);
  if (omp_set_levels) omp_set_levels(3);
  SuiteSparse_config.malloc_func = &host_malloc;
  SuiteSparse_config.calloc_func = &host_calloc;
  SuiteSparse_config.realloc_func = &host_realloc;
  SuiteSparse_config.free_func = &host_free;
  const ProcessState before = ProcessState::read();

  const Face f = bumpy(150);
  HostCholmod host;
  std::thread other([&] { host.run(before); });
  const std::vector<double> uv1 = solve(f, 1);
  const std::vector<double> uv2 = solve(f, 2);
  host.stop = true;
  other.join();

  expect_same(before, ProcessState::read());
  if (omp_get_levels) EXPECT(omp_get_levels() == 3);
  EXPECT(host.rounds > 0);
  EXPECT(host.wrong == 0);
  EXPECT(host.changed == 0);
  EXPECT(host_allocations.load() > 0);  // SuiteSparse, the host's and wefm's, allocated through the host's functions
  EXPECT(!uv1.empty());
  EXPECT(uv1.size() == uv2.size() && std::memcmp(uv1.data(), uv2.data(), uv1.size() * sizeof(double)) == 0);
  int64_t v = -1;
  EXPECT(wefm_get_process_policy(WEFM_PROCESS_BLAS_THREADS, &v) == WEFM_OK && v == 0);
  EXPECT(wefm_get_process_policy(WEFM_PROCESS_HUGE_PAGES, &v) == WEFM_OK && v == 0);
  std::printf("host CHOLMOD rounds during the solves: %d; BLAS threads %d; %s\n", host.rounds, before.blas_threads,
              blas_get && omp_get_levels ? "OpenBLAS and OpenMP found" : "OpenBLAS or OpenMP not loaded: their checks are void");
  return failures == 0 ? 0 : 1;
}

// Key 77, made in C (unknown_policy_key.c): the value is outside the C++ enum's range.
extern "C" wefm_status set_unknown_policy_key(int64_t value);
extern "C" wefm_status get_unknown_policy_key(int64_t* value);

int run_opt_in() {
  int64_t v = -1;
  EXPECT(set_unknown_policy_key(1) == WEFM_ERROR_INVALID_ARGUMENT);
  EXPECT(std::strstr(wefm_last_error(), "unknown key") != nullptr);
  EXPECT(get_unknown_policy_key(&v) == WEFM_ERROR_INVALID_ARGUMENT);
  EXPECT(wefm_get_process_policy(WEFM_PROCESS_HUGE_PAGES, nullptr) == WEFM_ERROR_NULL_ARGUMENT);
  EXPECT(wefm_set_process_policy(WEFM_PROCESS_HUGE_PAGES, 2) == WEFM_ERROR_INVALID_ARGUMENT);
  EXPECT(wefm_set_process_policy(WEFM_PROCESS_BLAS_THREADS, -1) == WEFM_ERROR_INVALID_ARGUMENT);
  EXPECT(wefm_set_process_policy(WEFM_PROCESS_BLAS_THREADS, 1025) == WEFM_ERROR_INVALID_ARGUMENT);
  EXPECT(wefm_get_process_policy(WEFM_PROCESS_BLAS_THREADS, &v) == WEFM_OK && v == 0);  // failures changed nothing

  // BLAS threads: the host's 2 stays until a solve, which sets the policy's 1.
  const Face f = bumpy(40);
  if (blas_set && blas_get) {
    blas_set(2);
    EXPECT(wefm_set_process_policy(WEFM_PROCESS_BLAS_THREADS, 1) == WEFM_OK);
    EXPECT(wefm_get_process_policy(WEFM_PROCESS_BLAS_THREADS, &v) == WEFM_OK && v == 1);
    EXPECT(blas_get() == 2);
    EXPECT(!solve(f, 1).empty());
    EXPECT(blas_get() == 1);
    EXPECT(wefm_set_process_policy(WEFM_PROCESS_BLAS_THREADS, 0) == WEFM_OK);
    blas_set(2);
    EXPECT(!solve(f, 1).empty());
    EXPECT(blas_get() == 2);
  } else {
    EXPECT(wefm_set_process_policy(WEFM_PROCESS_BLAS_THREADS, 1) == WEFM_ERROR_UNSUPPORTED);
  }

  // Huge pages: SuiteSparse's C-library allocator goes through wefm's wrappers and comes back; a
  // host's own allocator is never replaced.
  void* (*const libc_malloc)(size_t) = SuiteSparse_config.malloc_func;
  void* (*const libc_calloc)(size_t, size_t) = SuiteSparse_config.calloc_func;
  EXPECT(libc_malloc == &std::malloc);
  EXPECT(wefm_set_process_policy(WEFM_PROCESS_HUGE_PAGES, 1) == WEFM_OK);
  EXPECT(wefm_get_process_policy(WEFM_PROCESS_HUGE_PAGES, &v) == WEFM_OK && v == 1);
  EXPECT(SuiteSparse_config.malloc_func != libc_malloc);
  EXPECT(SuiteSparse_config.calloc_func != libc_calloc);
  EXPECT(!solve(f, 1).empty());  // CHOLMOD's blocks from the wrappers are freed by free()
  EXPECT(wefm_set_process_policy(WEFM_PROCESS_HUGE_PAGES, 0) == WEFM_OK);
  EXPECT(SuiteSparse_config.malloc_func == libc_malloc);
  EXPECT(SuiteSparse_config.calloc_func == libc_calloc);
  SuiteSparse_config.malloc_func = &host_malloc;
  SuiteSparse_config.calloc_func = &host_calloc;
  EXPECT(wefm_set_process_policy(WEFM_PROCESS_HUGE_PAGES, 1) == WEFM_OK);
  EXPECT(SuiteSparse_config.malloc_func == &host_malloc);
  EXPECT(SuiteSparse_config.calloc_func == &host_calloc);
  EXPECT(!solve(f, 1).empty());
  EXPECT(wefm_set_process_policy(WEFM_PROCESS_HUGE_PAGES, 0) == WEFM_OK);
  EXPECT(SuiteSparse_config.malloc_func == &host_malloc);
  return failures == 0 ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode == "default") return run_default();
  if (mode == "opt-in") return run_opt_in();
  std::fprintf(stderr, "usage: %s default|opt-in\n", argv[0]);
  return 2;
}
