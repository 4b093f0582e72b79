// Only with CAD import built (WEFM_WITH_OCCT): apps/cad is not on the include path otherwise.
#ifdef WEFM_CLI_HAVE_OCCT
#include "cad_plugin_loader.hpp"

#include <dlfcn.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <string_view>
#include <vector>

#include "cad_model_wire.hpp"
#include "child_process.hpp"
#include "exit_codes.hpp"
#include "stop.hpp"

namespace wefm_cli {

namespace {

std::string own_directory() {
  std::vector<char> buf(4096);
  const ssize_t n = readlink("/proc/self/exe", buf.data(), buf.size() - 1);
  if (n <= 0) return ".";
  std::string path(buf.data(), static_cast<size_t>(n));
  const size_t slash = path.rfind('/');
  return slash == std::string::npos ? std::string(".") : path.substr(0, slash);
}

std::vector<std::string> candidates() {
  if (const char* env = std::getenv("WEFM_CAD_PLUGIN"); env && *env) return {env};
  const std::string dir = own_directory();
  std::vector<std::string> c{dir + "/" + wefm_cad::kPluginFile};
#ifdef WEFM_CAD_PLUGIN_DIR
  c.push_back(dir + "/" + WEFM_CAD_PLUGIN_DIR + "/" + wefm_cad::kPluginFile);
#endif
  return c;
}

const wefm_cad::PluginApi* open_plugin(std::string& error) {
  std::string why;
  for (const std::string& path : candidates()) {
    if (access(path.c_str(), F_OK) != 0) {
      why += "\n  " + path + ": no such file";
      continue;
    }
    // RTLD_LOCAL: OCCT's symbols stay out of the global namespace; RTLD_NOW: a missing OCCT library
    // fails here, with dlerror naming it, not at the first call.
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
      const char* e = dlerror();
      why += "\n  " + path + ": " + (e ? e : "cannot be loaded");
      continue;
    }
    using Entry = const wefm_cad::PluginApi* (*)();
    const auto entry = reinterpret_cast<Entry>(dlsym(handle, wefm_cad::kPluginSymbol));
    const wefm_cad::PluginApi* api = entry ? entry() : nullptr;
    const wefm_cad::PluginApi expected;
    if (!api || api->abi != expected.abi || api->sizeof_model != expected.sizeof_model ||
        api->sizeof_face != expected.sizeof_face || api->sizeof_settings != expected.sizeof_settings || !api->load_model) {
      why += "\n  " + path + ": not a CAD plugin of this wefm (stale build or another version)";
      dlclose(handle);
      continue;
    }
    return api;
  }
  error = std::string("CAD import is not available: cannot load ") + wefm_cad::kPluginFile +
          " (Open CASCADE's libraries are needed; scripts/install-deps.sh installs them):" + why;
  return nullptr;
}

}  // namespace

int load_cad_model_via_plugin(const std::string& path, const wefm_cad::TessellationSettings& settings,
                              wefm_cad::CadModel& model, std::string& error) {
  static std::once_flag once;
  static const wefm_cad::PluginApi* api = nullptr;
  static std::string failure;
  std::call_once(once, [] { api = open_plugin(failure); });  // in this process: the child inherits it
  if (!api) {
    error = failure;
    return kExitIo;
  }
  // The child's answer: 'M' and the encoded model, or 'E' and the error message.
  auto import = [&]() -> std::string {
    wefm_cad::CadModel m;
    std::string e;
    if (!api->load_model(path, settings, m, e)) return "E" + e;
    return "M" + wefm_cad::encode_cad_model(m);
  };
  const double left = seconds_left();
  const double limit = left >= 0 ? left + 1 : kDefaultImportSeconds;  // the deadline itself stops it first
  // The machine's memory as the import's address-space cap: an import that would exceed it ends
  // with a message instead of swapping the machine or waking the OOM killer.
  const double memory_mb = physical_memory_mb();
  const ChildOutcome child = run_in_child(import, limit, memory_mb);
  switch (child.kind) {
    case ChildOutcome::kStopped:
      error = path + ": CAD import: " + stop_reason();
      return stop_exit_code();
    case ChildOutcome::kTimedOut: {
      char buf[160];
      std::snprintf(buf, sizeof buf, ": CAD import did not end within %g s (Open CASCADE); --time-limit sets the limit",
                    limit);
      error = path + buf;
      return kExitTimeLimit;
    }
    case ChildOutcome::kFailed:
      error = path + ": CAD import failed: the import process " + child.problem +
              (child.problem == "ran out of memory" ? " (its cap is the machine's " + std::to_string(static_cast<long long>(memory_mb)) + " MB)" : "");
      return kExitIo;
    case ChildOutcome::kDone: break;
  }
  if (!child.bytes.empty() && child.bytes[0] == 'E') {
    error = child.bytes.substr(1);
    return kExitIo;
  }
  if (child.bytes.empty() || child.bytes[0] != 'M' ||
      !wefm_cad::decode_cad_model(std::string_view(child.bytes).substr(1), model)) {
    error = path + ": CAD import failed: the import process handed back no model";
    return kExitIo;
  }
  return kExitOk;
}

}  // namespace wefm_cli

#endif  // WEFM_CLI_HAVE_OCCT
