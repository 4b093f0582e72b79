#pragma once
// Opens the CAD plugin (apps/cad/cad_plugin.hpp) on first use. Looks, in order, at the path in
// WEFM_CAD_PLUGIN, next to the `wefm` binary (the build tree), and in WEFM_CAD_PLUGIN_DIR relative
// to the binary's directory (the install tree: LIBDIR/wefm). Thread-safe; the module stays loaded.
#include <string>

#include "cad_plugin.hpp"

namespace wefm_cli {

// The plugin's table, or null with `error` saying where it looked and why each place failed.
const wefm_cad::PluginApi* cad_plugin(std::string& error);

}  // namespace wefm_cli
