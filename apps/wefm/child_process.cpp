#include "child_process.hpp"

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <new>
#include <fcntl.h>
#include <poll.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include "stop.hpp"

namespace wefm_cli {

namespace {

constexpr int kChildOutOfMemory = 3;

[[noreturn]] void child_main(int out_fd, pid_t parent, const std::function<std::string()>& work, double memory_mb) {
  // A Ctrl-C at the terminal reaches the child too: it may simply die, the parent reports it.
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (getppid() != parent) _exit(1);  // the parent died before the line above
#if defined(__SANITIZE_ADDRESS__)
  // AddressSanitizer reserves terabytes of address space for its shadow: no address-space cap can
  // apply in a sanitized build (the child would fail its first mmap).
  memory_mb = 0;
#endif
  if (memory_mb > 0) {
    const rlim_t bytes = static_cast<rlim_t>(memory_mb * 1048576.0);
    rlimit cur{};
    // Never raised above what the parent was given.
    if (getrlimit(RLIMIT_AS, &cur) == 0 && (cur.rlim_cur == RLIM_INFINITY || bytes < cur.rlim_cur)) {
      const rlimit cap{bytes, cur.rlim_max};
      setrlimit(RLIMIT_AS, &cap);
    }
  }
  int code = 0;
  try {
    const std::string bytes = work();
    for (size_t done = 0; done < bytes.size();) {
      const ssize_t n = write(out_fd, bytes.data() + done, bytes.size() - done);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        code = 1;
        break;
      }
      done += static_cast<size_t>(n);
    }
  } catch (const std::bad_alloc&) {
    code = kChildOutOfMemory;
  } catch (...) {
    code = 2;
  }
  // _exit: no atexit handlers or static destructors of the parent's state run twice.
  _exit(code);
}

std::string describe(int status) {
  char buf[96];
  if (WIFSIGNALED(status)) {
    const int sig = WTERMSIG(status);
    std::snprintf(buf, sizeof buf, "was killed by signal %d (%s)", sig, strsignal(sig));
  } else if (WEXITSTATUS(status) == kChildOutOfMemory) {
    std::snprintf(buf, sizeof buf, "ran out of memory");
  } else {
    std::snprintf(buf, sizeof buf, "ended with status %d", WEXITSTATUS(status));
  }
  return buf;
}

}  // namespace

double physical_memory_mb() {
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
  return pages > 0 && page > 0 ? static_cast<double>(pages) * static_cast<double>(page) / 1048576.0 : 0.0;
}

ChildOutcome run_in_child(const std::function<std::string()>& work, double seconds, double memory_mb) {
  ChildOutcome out;
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) {
    out.problem = std::string("cannot create a pipe: ") + std::strerror(errno);
    return out;
  }
  std::fflush(nullptr);  // buffered output must not be written twice, once by the child
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid < 0) {
    out.problem = std::string("cannot start a process: ") + std::strerror(errno);
    close(fds[0]);
    close(fds[1]);
    return out;
  }
  if (pid == 0) {
    close(fds[0]);
    child_main(fds[1], parent, work, memory_mb);
  }
  close(fds[1]);
  set_child_process(pid);
  const auto t0 = std::chrono::steady_clock::now();
  out.kind = ChildOutcome::kDone;
  char buf[1 << 16];
  for (;;) {
    if (interrupted()) {
      out.kind = ChildOutcome::kStopped;
      break;
    }
    if (seconds > 0 && std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() >= seconds) {
      out.kind = ChildOutcome::kTimedOut;
      break;
    }
    pollfd p{fds[0], POLLIN, 0};
    if (poll(&p, 1, 50) <= 0) continue;  // 50 ms: below what a user waiting on Ctrl-C notices
    const ssize_t n = read(fds[0], buf, sizeof buf);
    if (n < 0 && (errno == EINTR || errno == EAGAIN)) continue;
    if (n <= 0) break;  // end of the child's output
    out.bytes.append(buf, static_cast<size_t>(n));
  }
  close(fds[0]);
  if (out.kind != ChildOutcome::kDone) kill(pid, SIGKILL);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  set_child_process(0);
  if (out.kind == ChildOutcome::kDone && !(WIFEXITED(status) && WEXITSTATUS(status) == 0)) {
    // A child that a Ctrl-C at the terminal ended is a stop, not a failure.
    out.kind = interrupted() ? ChildOutcome::kStopped : ChildOutcome::kFailed;
    out.problem = describe(status);
    out.bytes.clear();
  }
  return out;
}

}  // namespace wefm_cli
