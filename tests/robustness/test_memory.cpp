// Memory exhaustion is a status, not a process kill: the address space of this process is capped
// with setrlimit(RLIMIT_AS) so that allocations inside the library fail, and every call must return
// WEFM_ERROR_OUT_OF_MEMORY (or another clean status) and leave the face usable once memory is back.
#include <doctest/doctest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "capi_meshes.hpp"

using namespace wefm_test;

namespace {

// Current virtual memory size of this process in bytes (VmSize).
long long vm_size() {
  std::ifstream f("/proc/self/status");
  std::string line;
  while (std::getline(f, line))
    if (line.rfind("VmSize:", 0) == 0) return std::stoll(line.substr(7)) * 1024;
  return -1;
}

// Lowers the soft address-space limit to the current size plus `headroom`; restores it on scope exit.
class AddressSpaceCap {
 public:
  explicit AddressSpaceCap(long long headroom) {
    getrlimit(RLIMIT_AS, &old_);
    rlimit r = old_;
    r.rlim_cur = static_cast<rlim_t>(vm_size() + headroom);
    ok_ = vm_size() > 0 && setrlimit(RLIMIT_AS, &r) == 0;
  }
  ~AddressSpaceCap() { setrlimit(RLIMIT_AS, &old_); }
  bool ok() const { return ok_; }

 private:
  rlimit old_{};
  bool ok_ = false;
};

}  // namespace

TEST_CASE("set_mesh under a memory cap returns OUT_OF_MEMORY and keeps the previous mesh") {
  const Arrays small = flat(4);
  Face f(small);
  REQUIRE(f.last == WEFM_OK);
  // 1.6 M vertices, 3.2 M triangles: the face's copy and its validation need ~300 MB.
  const Arrays big = flat(1270);
  wefm_status s;
  {
    AddressSpaceCap cap(64ll << 20);
    REQUIRE(cap.ok());
    s = wefm_face_set_mesh(f, big.nv(), big.xyz.data(), big.nt(), big.tri.data());
  }
  INFO(f.error());
  CHECK(s == WEFM_ERROR_OUT_OF_MEMORY);
  CHECK(use_count(f) == small.nv());
  CHECK(wefm_face_solve(f) == WEFM_OK);
  // With the memory back the same call succeeds.
  CHECK(wefm_face_set_mesh(f, big.nv(), big.xyz.data(), big.nt(), big.tri.data()) == WEFM_OK);
}

TEST_CASE("a solve under a memory cap fails cleanly and keeps the previous result") {
  // 250 x 250 cells: the factorisation and the continuation need well over 32 MB.
  for (int solver : {WEFM_SOLVER_EIGEN, WEFM_SOLVER_CHOLMOD}) {
    if (solver == WEFM_SOLVER_CHOLMOD && !wefm_has_suitesparse()) continue;
    CAPTURE(solver);
    Face f(cap(250));
    REQUIRE(f.last == WEFM_OK);
    wefm_options o = options();
    o.solver = solver;
    o.s = 0;
    REQUIRE(wefm_face_set_options(f, &o) == WEFM_OK);
    REQUIRE(wefm_face_build(f) == WEFM_OK);
    wefm_status s;
    {
      AddressSpaceCap cap(32ll << 20);
      REQUIRE(cap.ok());
      s = wefm_face_solve(f);
    }
    MESSAGE("solver ", solver, " under a 32 MB cap: ", std::string(wefm_status_string(s)), ": ", f.error());
    // CHOLMOD reports its own allocation failures through its status, in the factorisation and in
    // the solves alike; the wrapper maps that status to OUT_OF_MEMORY (a failed cholmod_solve once
    // went unnoticed and came back as SINGULAR from garbage).
    CHECK(s == WEFM_ERROR_OUT_OF_MEMORY);
    int32_t solved = 1;
    wefm_face_has_result(f, &solved);
    CHECK(solved == 0);
    CHECK(wefm_face_solve(f) == WEFM_OK);  // memory back: the same face solves
  }
}

TEST_CASE("memory_limit_mb refuses a solve estimated above it before factorising; the previous result stays") {
  // 60 x 60 cells: about 7,200 triangles, a factor of some 10^5 entries (a few MB with the rest).
  for (int solver : {WEFM_SOLVER_EIGEN, WEFM_SOLVER_CHOLMOD}) {
    if (solver == WEFM_SOLVER_CHOLMOD && !wefm_has_suitesparse()) continue;
    CAPTURE(solver);
    Face f(cap(60));
    REQUIRE(f.last == WEFM_OK);
    wefm_options o = options();
    o.solver = solver;
    o.s = 1;
    REQUIRE(wefm_face_set_options(f, &o) == WEFM_OK);
    REQUIRE(wefm_face_solve(f) == WEFM_OK);
    wefm_report before;
    wefm_report_init(&before);
    REQUIRE(wefm_face_get_report(f, &before) == WEFM_OK);
    o.memory_limit_mb = 1;  // below any estimate: refused, whatever the face
    REQUIRE(wefm_face_set_options(f, &o) == WEFM_OK);
    CHECK(wefm_face_solve(f) == WEFM_ERROR_OUT_OF_MEMORY);
    const std::string msg = f.error();
    MESSAGE(msg);
    CHECK(msg.find("memory_limit_mb") != std::string::npos);
    int32_t solved = 0;
    wefm_face_has_result(f, &solved);
    CHECK(solved == 1);  // the previous result stays
    wefm_report after;
    wefm_report_init(&after);
    REQUIRE(wefm_face_get_report(f, &after) == WEFM_OK);
    CHECK(after.score == before.score);
    o.memory_limit_mb = 1e5;  // far above: the same solve goes through
    REQUIRE(wefm_face_set_options(f, &o) == WEFM_OK);
    CHECK(wefm_face_solve(f) == WEFM_OK);
  }
}

TEST_CASE("a solve whose threads cannot be started runs on the calling thread, with the same layout") {
  // A solve of 20,000 uses and more on 2 threads starts threads for its coefficients and its
  // symbolic analysis. A thread's stack is sized by RLIMIT_STACK as the process started, so in a
  // child started with 1 GB stacks under a 512 MB address-space cap no thread can start, while
  // every allocation fits. The child exits with the solve's status, or 120 if the layout differs
  // from the same solve's once the cap is lifted (layouts do not depend on the thread count).
  if (std::getenv("WEFM_TEST_THREAD_OOM_CHILD")) {
    Face f(cap(150));
    wefm_options o = options();
    o.threads = 2;
    if (f.last != WEFM_OK || wefm_face_set_options(f, &o) != WEFM_OK || wefm_face_build(f) != WEFM_OK) std::_Exit(100);
    wefm_status s;
    {
      AddressSpaceCap cap(512ll << 20);
      if (!cap.ok()) std::_Exit(101);
      s = wefm_face_solve(f);
    }
    std::fprintf(stderr, "child: %s: %s\n", wefm_status_string(s), f.error().c_str());
    if (s != WEFM_OK) std::_Exit(static_cast<int>(s));
    const std::vector<double> capped = get_uv(f);
    if (wefm_face_solve(f) != WEFM_OK) std::_Exit(121);
    std::_Exit(get_uv(f) == capped ? 0 : 120);
  }
  const pid_t pid = fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    rlimit r{};
    getrlimit(RLIMIT_STACK, &r);
    r.rlim_cur = rlim_t(1) << 30;
    if (r.rlim_max != RLIM_INFINITY && r.rlim_max < r.rlim_cur) r.rlim_max = r.rlim_cur;
    if (setrlimit(RLIMIT_STACK, &r) != 0) std::_Exit(102);
    setenv("WEFM_TEST_THREAD_OOM_CHILD", "1", 1);
    setenv("OPENBLAS_NUM_THREADS", "1", 1);
    execl("/proc/self/exe", "wefm_memory_test", "-tc=a solve whose threads cannot be started*", static_cast<char*>(nullptr));
    std::_Exit(103);
  }
  int status = 0;
  REQUIRE(waitpid(pid, &status, 0) == pid);
  REQUIRE(WIFEXITED(status));
  INFO("child exit code ", WEXITSTATUS(status), " (100-103: set-up failed, 120: another layout)");
  CHECK(WEXITSTATUS(status) == 0);
}
