#include "stop.hpp"

#include <array>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <unistd.h>

#include "exit_codes.hpp"

namespace wefm_cli {

namespace {

using Clock = std::chrono::steady_clock;

std::atomic<int> g_signal{0};          // the first stop signal received
std::atomic<bool> g_timed_out{false};
std::atomic<int64_t> g_deadline_ns{0};  // steady clock; 0 = no deadline
std::atomic<double> g_limit_seconds{0};
std::atomic<pid_t> g_child{0};
static_assert(std::atomic<int>::is_always_lock_free && std::atomic<int64_t>::is_always_lock_free &&
                  std::atomic<pid_t>::is_always_lock_free,
              "the signal handler needs lock-free atomics");

// Fixed storage, so the handler reads paths without touching the heap. A slot's path is written
// before its state becomes kLive, and the handler only reads kLive slots.
constexpr int kSlots = 256;
constexpr size_t kPathMax = 4096;
enum SlotState : int { kFree = 0, kClaimed = 1, kLive = 2 };
std::array<std::atomic<int>, kSlots> g_slot_state{};
char g_slot_path[kSlots][kPathMax];

int64_t now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now().time_since_epoch()).count();
}

extern "C" void on_stop_signal(int sig) {
  int expected = 0;
  if (g_signal.compare_exchange_strong(expected, sig)) return;  // first: the stages see the flag
  // Second: only async-signal-safe calls from here on.
  for (int i = 0; i < kSlots; ++i)
    if (g_slot_state[static_cast<size_t>(i)].load() == kLive) unlink(g_slot_path[i]);
  if (const pid_t child = g_child.load(); child > 0) kill(child, SIGKILL);
  std::signal(sig, SIG_DFL);
  raise(sig);
}

}  // namespace

namespace {

sigset_t stop_signals() {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  return set;
}

}  // namespace

void hold_stop_signals() {
  const sigset_t set = stop_signals();
  sigprocmask(SIG_BLOCK, &set, nullptr);
}

void install_stop_handlers() {
  struct sigaction sa;
  std::memset(&sa, 0, sizeof sa);
  sa.sa_handler = on_stop_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESTART;  // reads and writes resume; the stages poll the flag
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
  const sigset_t set = stop_signals();
  sigprocmask(SIG_UNBLOCK, &set, nullptr);
}

bool interrupted() {
  if (g_signal.load() != 0 || g_timed_out.load()) return true;
  const int64_t deadline = g_deadline_ns.load();
  if (deadline != 0 && now_ns() >= deadline) {
    g_timed_out.store(true);
    return true;
  }
  return false;
}

int stop_exit_code() { return g_signal.load() == 0 && g_timed_out.load() ? kExitTimeLimit : kExitCancelled; }

int exit_after_stop(int exit_code, const std::string& what) {
  if (!interrupted()) return exit_code;
  std::fprintf(stderr, "wefm: %s: %s\n", what.c_str(), stop_reason().c_str());
  return stop_exit_code();
}

std::string stop_reason() {
  if (const int sig = g_signal.load(); sig != 0) return sig == SIGTERM ? "cancelled (SIGTERM)" : "cancelled (Ctrl-C)";
  if (g_timed_out.load()) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "time limit of %g s reached (--time-limit)", g_limit_seconds.load());
    return buf;
  }
  return "not stopped";
}

void set_time_limit(double seconds) {
  g_limit_seconds.store(seconds);
  g_deadline_ns.store(now_ns() + static_cast<int64_t>(seconds * 1e9));
}

double seconds_left() {
  const int64_t deadline = g_deadline_ns.load();
  if (deadline == 0) return -1;
  return std::max(0.0, static_cast<double>(deadline - now_ns()) * 1e-9);
}

int register_temporary(const std::string& path) {
  if (path.size() >= kPathMax) return -1;
  for (int i = 0; i < kSlots; ++i) {
    int expected = kFree;
    if (!g_slot_state[static_cast<size_t>(i)].compare_exchange_strong(expected, kClaimed)) continue;
    std::memcpy(g_slot_path[i], path.c_str(), path.size() + 1);
    g_slot_state[static_cast<size_t>(i)].store(kLive);
    return i;
  }
  return -1;
}

void unregister_temporary(int slot) {
  if (slot >= 0 && slot < kSlots) g_slot_state[static_cast<size_t>(slot)].store(kFree);
}

void set_child_process(pid_t pid) { g_child.store(pid); }

}  // namespace wefm_cli
