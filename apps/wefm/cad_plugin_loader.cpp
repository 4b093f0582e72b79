// Only with CAD import built (WEFM_WITH_OCCT): apps/cad is not on the include path otherwise.
#ifdef WEFM_CLI_HAVE_OCCT
#include "cad_plugin_loader.hpp"

#include <dlfcn.h>
#include <unistd.h>

#include <cstdlib>
#include <mutex>
#include <vector>

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

bool load_cad_model_via_plugin(const std::string& path, const wefm_cad::TessellationSettings& settings,
                               wefm_cad::CadModel& model, std::string& error) {
  static std::once_flag once;
  static const wefm_cad::PluginApi* api = nullptr;
  static std::string failure;
  std::call_once(once, [] { api = open_plugin(failure); });
  if (!api) {
    error = failure;
    return false;
  }
  return api->load_model(path, settings, model, error);
}

}  // namespace wefm_cli

#endif  // WEFM_CLI_HAVE_OCCT
