// run_in_child (apps/wefm/child_process.hpp), the wrapper of the CAD import: the child's answer comes
// back whole, a crash or exit is a failure that names it, the time limit kills the child, and the
// memory cap makes a runaway allocation fail in the child while the parent's limits stay as they were.
#include <doctest/doctest.h>
#include <sys/resource.h>
#include <unistd.h>

#include <csignal>
#include <cstdlib>
#include <string>
#include <vector>

#include "child_process.hpp"

using wefm_cli::ChildOutcome;
using wefm_cli::run_in_child;

TEST_CASE("run_in_child hands back the child's bytes") {
  const ChildOutcome c = run_in_child([] { return std::string(300000, 'x') + "end"; }, 60);
  CHECK(c.kind == ChildOutcome::kDone);
  CHECK(c.bytes.size() == 300003);
  CHECK(c.bytes.substr(c.bytes.size() - 3) == "end");
}

TEST_CASE("run_in_child: a child killed by a signal is a failure naming the signal") {
  // SIGKILL: no handler in the child (doctest's, a sanitizer's) can turn it into an exit status.
  const ChildOutcome c = run_in_child([]() -> std::string { kill(getpid(), SIGKILL); return ""; }, 60);
  CHECK(c.kind == ChildOutcome::kFailed);
  CHECK(c.problem.find("signal 9") != std::string::npos);
  CHECK(c.bytes.empty());
}

TEST_CASE("run_in_child: the time limit kills a child that does not end") {
  const ChildOutcome c = run_in_child([]() -> std::string { for (;;) pause(); }, 0.3);
  CHECK(c.kind == ChildOutcome::kTimedOut);
}

// run_in_child applies no cap under AddressSanitizer (its shadow reservation exceeds any).
#if !defined(__SANITIZE_ADDRESS__)
TEST_CASE("run_in_child: the memory cap fails a runaway allocation in the child, not the parent") {
  rlimit before{};
  REQUIRE(getrlimit(RLIMIT_AS, &before) == 0);
  const ChildOutcome c = run_in_child(
      [] {
        std::vector<char> big(size_t(4) << 30, 1);  // 4 GB against a 512 MB cap
        return std::string(1, big[12345]);
      },
      60, 512);
  CHECK(c.kind == ChildOutcome::kFailed);
  CHECK(c.problem == "ran out of memory");
  rlimit after{};
  REQUIRE(getrlimit(RLIMIT_AS, &after) == 0);
  CHECK(after.rlim_cur == before.rlim_cur);
  // Under the cap the same child works.
  const ChildOutcome ok = run_in_child([] { return std::string(std::vector<char>(size_t(64) << 20, 'a').data(), 4); }, 60, 512);
  CHECK(ok.kind == ChildOutcome::kDone);
  CHECK(ok.bytes == "aaaa");
  CHECK(wefm_cli::physical_memory_mb() > 0);
}
#endif
