// Distinct faces solve concurrently with the same results as one after another; a cancel from another
// thread stops a long solve promptly and keeps the previous result (wefm.h "Threads").
#include <doctest/doctest.h>

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <thread>

#include "capi_meshes.hpp"

using namespace wefm_test;

namespace {

// Under ThreadSanitizer everything runs ~10x slower: smaller faces, fewer rounds.
#if defined(__SANITIZE_THREAD__)
constexpr int kScale = 1;
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
constexpr int kScale = 1;
#else
constexpr int kScale = 2;
#endif
#else
constexpr int kScale = 2;
#endif

// Face k of the set: different shapes and options so threads do not all do the same work.
struct Job {
  Arrays mesh;
  wefm_options opt;
  std::vector<int32_t> seams;
};

Job make_job(int k) {
  Job j;
  j.opt = options();
  j.opt.max_rho_iterations = 8;
  switch (k % 4) {
    case 0: j.mesh = cap(6 * kScale + k); break;
    case 1: j.mesh = flat(5 * kScale + k); j.opt.s = 2; break;
    case 2:
      j.mesh = open_cylinder(8 * kScale, 2 + k % 3);
      for (int r = 0; r < 2 + k % 3; ++r) j.seams.insert(j.seams.end(), {r * 8 * kScale, (r + 1) * 8 * kScale});
      break;
    default: j.mesh = cap(5 * kScale + k); j.opt.method = WEFM_METHOD_ROLLOUT; j.opt.max_rollout_sweeps = 300; break;
  }
  return j;
}

// Solves the job on a fresh face; returns status and UVs bit for bit.
std::pair<wefm_status, std::vector<double>> run(const Job& j) {
  Face f(j.mesh);
  if (f.last != WEFM_OK) return {f.last, {}};
  wefm_face_set_options(f, &j.opt);
  if (!j.seams.empty()) wefm_face_add_seams(f, static_cast<int64_t>(j.seams.size() / 2), j.seams.data());
  const wefm_status s = wefm_face_solve(f);
  return {s, get_uv(f)};
}

bool bitwise_equal(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

}  // namespace

TEST_CASE("8 threads solving their own faces repeatedly give the sequential results bit for bit") {
  constexpr int kThreads = 8, kRounds = 3;
  std::vector<Job> jobs;
  std::vector<std::pair<wefm_status, std::vector<double>>> expected;
  for (int k = 0; k < kThreads; ++k) {
    jobs.push_back(make_job(k));
    expected.push_back(run(jobs.back()));
    INFO("job ", k, ": ", std::string(wefm_status_string(expected.back().first)));
    REQUIRE((expected.back().first == WEFM_OK || expected.back().first == WEFM_ERROR_NOT_CONVERGED));
    REQUIRE(!expected.back().second.empty());
  }
  std::atomic<int> mismatches{0}, done{0};
  std::vector<std::thread> pool;
  for (int k = 0; k < kThreads; ++k)
    pool.emplace_back([&, k] {
      for (int r = 0; r < kRounds; ++r) {
        const auto got = run(jobs[static_cast<size_t>(k)]);
        if (got.first != expected[static_cast<size_t>(k)].first || !bitwise_equal(got.second, expected[static_cast<size_t>(k)].second))
          mismatches.fetch_add(1);
        done.fetch_add(1);
      }
    });
  for (auto& t : pool) t.join();
  CHECK(done.load() == kThreads * kRounds);
  CHECK(mismatches.load() == 0);
}

TEST_CASE("one face's solve on 2 threads (the analysis run ahead on a thread of its own) gives the 1-thread bits") {
  // 151 x 151 vertices: above the size where the analysis runs beside the coefficients
  // (core/include/wefm/core/solve/early_analysis.hpp), with the boundary term on its loop.
  Job j;
  j.mesh = flat(150);
  j.opt = options();
  j.opt.s = 0;
  j.opt.threads = 1;
  const auto one = run(j);
  REQUIRE(one.first == WEFM_OK);
  j.opt.threads = 2;
  for (int r = 0; r < 2; ++r) {
    const auto two = run(j);
    CHECK(two.first == WEFM_OK);
    CHECK(bitwise_equal(two.second, one.second));
  }
}

TEST_CASE("threads with their own mesh handles and their own error messages") {
  const Arrays a = flat(6);
  std::atomic<int> bad{0};
  std::vector<std::thread> pool;
  for (int k = 0; k < 8; ++k)
    pool.emplace_back([&, k] {
      for (int r = 0; r < 5; ++r) {
        wefm_mesh* m = nullptr;
        if (wefm_mesh_create(a.nv(), a.xyz.data(), a.nt(), a.tri.data(), &m) != WEFM_OK) {
          bad.fetch_add(1);
          continue;
        }
        wefm_mesh_info info;
        wefm_mesh_info_init(&info);
        if (wefm_mesh_get_info(m, &info) != WEFM_OK || info.vertices != a.nv()) bad.fetch_add(1);
        wefm_face* f = nullptr;
        wefm_face_create(&f);
        if (wefm_face_set_mesh_from(f, m) != WEFM_OK) bad.fetch_add(1);
        wefm_mesh_release(m);  // the face copied it
        // A failure message (on the handle and thread-local) names this thread's own bad index.
        int32_t id;
        const std::string mine = std::to_string(1000 + 10 * k + r);
        if (wefm_face_add_pin(f, 1000 + 10 * k + r, 0, 0, &id) != WEFM_ERROR_INVALID_CONSTRAINT) bad.fetch_add(1);
        if (std::string(wefm_face_last_error(f)).find(mine) == std::string::npos) bad.fetch_add(1);
        if (std::string(wefm_last_error()).find(mine) == std::string::npos) bad.fetch_add(1);
        if (wefm_face_solve(f) != WEFM_OK) bad.fetch_add(1);
        wefm_face_release(f);
      }
    });
  for (auto& t : pool) t.join();
  CHECK(bad.load() == 0);
}

TEST_CASE("one mesh handle read by many threads at once (wefm.h: a wefm_mesh never changes)") {
  const Arrays a = flat(12);
  wefm_mesh* m = nullptr;
  REQUIRE(wefm_mesh_create(a.nv(), a.xyz.data(), a.nt(), a.tri.data(), &m) == WEFM_OK);
  wefm_mesh_info ref;
  wefm_mesh_info_init(&ref);
  REQUIRE(wefm_mesh_get_info(m, &ref) == WEFM_OK);
  std::atomic<int> bad{0};
  std::vector<std::thread> pool;
  for (int k = 0; k < 6; ++k)
    pool.emplace_back([&, k] {
      for (int r = 0; r < 4; ++r) {
        wefm_mesh_retain(m);
        if (k % 2 == 0) {  // the statistics and a copy of the arrays, as the `wefm` tool takes them
          wefm_mesh_info info;
          wefm_mesh_info_init(&info);
          std::vector<double> xyz(static_cast<size_t>(3 * a.nv()));
          int64_t n = 0;
          if (wefm_mesh_get_info(m, &info) != WEFM_OK || info.triangles != ref.triangles || info.area != ref.area) bad.fetch_add(1);
          if (wefm_mesh_get_vertices(m, xyz.data(), 3 * a.nv(), &n) != WEFM_OK || xyz != a.xyz) bad.fetch_add(1);
        } else {  // a face built and solved from it meanwhile
          wefm_face* f = nullptr;
          wefm_face_create(&f);
          if (wefm_face_set_mesh_from(f, m) != WEFM_OK || wefm_face_build(f) != WEFM_OK || wefm_face_solve(f) != WEFM_OK)
            bad.fetch_add(1);
          wefm_face_release(f);
        }
        wefm_mesh_release(m);
      }
    });
  for (auto& t : pool) t.join();
  wefm_mesh_release(m);
  CHECK(bad.load() == 0);
}

namespace {

struct CancelProbe {
  std::atomic<int> calls{0};
  std::atomic<bool> in_continuation{false};
  std::atomic<int> cancel_after{-1};  // progress callback returns non-zero from this call on
};

int probe_progress(void* user, double, const char* stage) {
  auto* p = static_cast<CancelProbe*>(user);
  const int n = p->calls.fetch_add(1) + 1;
  if (std::strcmp(stage, "continuation") == 0) p->in_continuation.store(true);
  const int after = p->cancel_after.load();
  return after >= 0 && n >= after ? 1 : 0;
}

// A face whose solve takes seconds: many continuation steps on a curved patch.
Arrays long_face() { return cap(kScale == 1 ? 40 : 70); }

wefm_options long_options() {
  wefm_options o = options();
  o.s = 2;
  o.s_step = 0.01;
  o.rho_tolerance = 1e-14;
  o.max_rho_iterations = 50;
  return o;
}

}  // namespace

TEST_CASE("wefm_face_cancel from another thread stops a long solve promptly; the previous result stays") {
  Face f(long_face());
  REQUIRE(f.last == WEFM_OK);
  // A first, quick solve gives the result that must survive the cancelled one.
  wefm_options quick = options();
  quick.s = 0;
  REQUIRE(wefm_face_set_options(f, &quick) == WEFM_OK);
  REQUIRE(wefm_face_solve(f) == WEFM_OK);
  const std::vector<double> before = get_uv(f);
  const wefm_options slow = long_options();
  REQUIRE(wefm_face_set_options(f, &slow) == WEFM_OK);
  CancelProbe probe;
  REQUIRE(wefm_face_set_progress_callback(f, probe_progress, &probe) == WEFM_OK);

  using clock = std::chrono::steady_clock;
  std::atomic<wefm_status> status{WEFM_OK};
  std::atomic<bool> finished{false};
  clock::time_point t_end;
  std::thread solver([&] {
    status.store(wefm_face_solve(f));
    t_end = clock::now();
    finished.store(true);
  });
  // Wait until the solve is well inside the continuation, then cancel.
  const auto t_wait = clock::now();
  while (!probe.in_continuation.load() && !finished.load() && clock::now() - t_wait < std::chrono::seconds(120))
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  REQUIRE_MESSAGE(!finished.load(), "the long solve finished before it could be cancelled; make it longer");
  const auto t_cancel = clock::now();
  CHECK(wefm_face_cancel(f) == WEFM_OK);
  solver.join();
  const double latency = std::chrono::duration<double>(t_end - t_cancel).count();
  MESSAGE("cancel latency: ", latency * 1000, " ms after ", probe.calls.load(), " progress calls");
  CHECK(status.load() == WEFM_ERROR_CANCELLED);
  CHECK(latency < 2.0);
  CHECK(std::string(f.error()).find("cancel") != std::string::npos);
  int32_t solved = 0;
  CHECK(wefm_face_has_result(f, &solved) == WEFM_OK);
  CHECK(solved == 1);
  CHECK(get_uv(f) == before);
  // The face is still usable: a new quick solve works and gives the same layout.
  REQUIRE(wefm_face_set_options(f, &quick) == WEFM_OK);
  CHECK(wefm_face_solve(f) == WEFM_OK);
  CHECK(get_uv(f) == before);
}

TEST_CASE("a progress callback returning non-zero cancels; the previous result stays") {
  Face f(cap(12));
  REQUIRE(f.last == WEFM_OK);
  REQUIRE(wefm_face_solve(f) == WEFM_OK);
  const std::vector<double> before = get_uv(f);
  CancelProbe probe;
  REQUIRE(wefm_face_set_progress_callback(f, probe_progress, &probe) == WEFM_OK);
  for (int after : {1, 2, 3, 5, 8}) {
    probe.calls.store(0);
    probe.cancel_after.store(after);
    CHECK(wefm_face_solve(f) == WEFM_ERROR_CANCELLED);
    CHECK(probe.calls.load() == after);  // no callback after the one that cancelled
    CHECK(get_uv(f) == before);
  }
  probe.cancel_after.store(-1);
  CHECK(wefm_face_solve(f) == WEFM_OK);
  CHECK(get_uv(f) == before);
}
