#pragma once
// Opens the CAD plugin (apps/cad/cad_plugin.hpp) on first use. Looks, in order, at the path in
// WEFM_CAD_PLUGIN, next to the `wefm` binary (the build tree), and in WEFM_CAD_PLUGIN_DIR relative
// to the binary's directory (the install tree: LIBDIR/wefm). Thread-safe; the module stays loaded.
#include <string>

#include "cad_plugin.hpp"

namespace wefm_cli {

// wefm_cad::load_cad_model (cad_model.hpp) through the plugin. False with `error` when the model
// cannot be read, or when the plugin cannot be opened (then `error` says where it looked and why
// each place failed).
bool load_cad_model_via_plugin(const std::string& path, const wefm_cad::TessellationSettings& settings,
                               wefm_cad::CadModel& model, std::string& error);

}  // namespace wefm_cli
