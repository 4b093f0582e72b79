// wefm: command-line front end of the wefm library, built only on the public C header.
#include <unistd.h>

#include <cstdio>
#include <exception>
#include <string>
#include <system_error>
#include <vector>

#include "command.hpp"
#include "exit_codes.hpp"
#include "huge_page_malloc.hpp"
#include "process_policy.hpp"
#include "stop.hpp"
#include "wefm/wefm.h"

#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/lsan_interface.h>
#endif

namespace {

void print_main_help() {
  std::printf(
      "wefm %s: flatten 3D triangulated faces into 2D domains (Weighted Edge Flattening Method)\n\n"
      "Usage: wefm COMMAND [options]\n"
      "       wefm COMMAND --help     options of one command, with their defaults\n"
      "       wefm --version\n\n"
      "Commands:\n",
      wefm_version());
  for (const auto& c : wefm_cli::commands()) std::printf("  %-10s %s\n", c.name, c.summary);
  std::printf("\nExample:\n  wefm flatten examples/data/vessel_patch.obj -o out/vessel_patch.obj "
              "--report out/report.json --svg out/domain.svg\n\n%s",
              wefm_cli::exit_codes_help());
}

int run(int argc, char** argv) {
  using namespace wefm_cli;
  if (argc < 2) {
    print_main_help();
    return kExitUsage;
  }
  const std::string first = argv[1];
  if (first == "--help" || first == "-h" || first == "help") {
    print_main_help();
    return kExitOk;
  }
  if (first == "--version" || first == "-V") {
    std::printf("wefm %s (%s)\n", wefm_version(), wefm_has_suitesparse() ? "CHOLMOD" : "Eigen solvers only");
    if (wefm_version_number() != WEFM_VERSION_NUMBER)
      std::fprintf(stderr, "wefm: warning: built against header %d but running library %d\n", WEFM_VERSION_NUMBER,
                   wefm_version_number());
    return kExitOk;
  }
  for (const auto& c : commands()) {
    if (first != c.name) continue;
    const int code = c.run(std::vector<std::string>(argv + 2, argv + argc));
    // A stage that failed because it was stopped reports the stop, whatever it made of it.
    return interrupted() && code != kExitOk && code != kExitUsage ? stop_exit_code() : code;
  }
  std::fprintf(stderr, "wefm: unknown command '%s' (try wefm --help)\n", first.c_str());
  return kExitUsage;
}

}  // namespace

namespace {

// The tool ends without running the libraries' finalisers: its outputs are complete and closed by
// then (OutputFile), and OpenBLAS's finaliser joins OpenBLAS's own pool threads, one of which, under
// an address-space limit (`ulimit -v`), retries the allocation of its work buffer without end: the
// process would hang at exit after having reported its result.
[[noreturn]] void end_process(int code) {
  std::fflush(nullptr);
#if defined(__SANITIZE_ADDRESS__)
  __lsan_do_leak_check();  // what exit() would have run: leak checking stays on in sanitized builds
#endif
  _exit(code);
}

}  // namespace

#if defined(__linux__)
namespace {

// The stop signals are held before any shared library's initialiser runs (the executable's ELF
// pre-init array comes first): OpenBLAS starts its pool threads while it loads, and a thread started
// with SIGINT and SIGTERM open takes a Ctrl-C by their default action, ending the process before
// main() has a handler (seen as exit -15 in cli.output_signals). Started after this, every such
// thread inherits the held signals for good, so they reach the thread that opens them in main().
void hold_before_libraries(int, char**, char**) { wefm_cli::hold_stop_signals(); }
__attribute__((section(".preinit_array"), used)) void (*const kHoldBeforeLibraries)(int, char**, char**) = hold_before_libraries;

}  // namespace
#endif

int main(int argc, char** argv) {
  // One handler for every command and stage (stop.hpp); the commands poll it. The signals are held
  // (from before the libraries load, above) over the re-exec, which resets handlers but keeps the
  // mask and pending signals, so a Ctrl-C at that moment waits for the handler instead of killing
  // the process.
  wefm_cli::hold_stop_signals();
  wefm_cli::reexec_with_huge_page_malloc(argc, argv);
  wefm_cli::install_stop_handlers();
  wefm_cli::opt_in_process_policy();
  // No exception may escape: an unexpected one (std::bad_alloc while writing outputs) becomes a
  // message and the solver-failure code rather than std::terminate.
  int code = wefm_cli::kExitSolver;
  try {
    code = run(argc, argv);
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "wefm: out of memory\n");
  } catch (const std::system_error& e) {
    // A thread that cannot start (its stack under `ulimit -v`) is exhausted memory, as in the library.
    const bool exhausted = e.code() == std::errc::not_enough_memory || e.code() == std::errc::resource_unavailable_try_again;
    std::fprintf(stderr, "wefm: %s: %s\n", exhausted ? "out of memory" : "internal error", e.what());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "wefm: internal error: %s\n", e.what());
  } catch (...) {
    std::fprintf(stderr, "wefm: internal error\n");
  }
  end_process(code);
}
