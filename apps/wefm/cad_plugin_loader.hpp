#pragma once
// Opens the CAD plugin (apps/cad/cad_plugin.hpp) on first use. Looks, in order, at the path in
// WEFM_CAD_PLUGIN, next to the `wefm` binary (the build tree), and in WEFM_CAD_PLUGIN_DIR relative
// to the binary's directory (the install tree: LIBDIR/wefm). Thread-safe; the module stays loaded.
#include <string>

#include "cad_plugin.hpp"

namespace wefm_cli {

// wefm_cad::load_cad_model (cad_model.hpp) through the plugin, run in a child process that hands the
// model back through a pipe: Open CASCADE cannot be interrupted (a mutated STEP file can keep it
// busy for hours), so the child is killed on a stop request (stop.hpp: Ctrl-C, SIGTERM, the
// --time-limit deadline) or after kDefaultImportSeconds when there is no deadline, and a crash in
// Open CASCADE ends the child, not the tool. The child's address space is capped at the machine's
// physical memory. Returns kExitOk, or with `error`: kExitIo when the model
// cannot be read, the plugin cannot be opened (`error` says where it looked and why each place
// failed) or the import crashed; stop_exit_code() when stopped; kExitTimeLimit at the import's
// default limit.
int load_cad_model_via_plugin(const std::string& path, const wefm_cad::TessellationSettings& settings,
                              wefm_cad::CadModel& model, std::string& error);

}  // namespace wefm_cli
