#pragma once
// The CAD import as a plugin: Open CASCADE is loaded only by the commands that read a CAD model.
// Linked into the `wefm` tool, OCCT's many libraries would be loaded and relocated by every run of
// every command, much of a small face's run, and the tool would need them even to flatten an OBJ.
// The module `wefm-cad-occt.so` holds load_cad_model and everything under it; the CLI opens it
// with dlopen when a model command runs.
// Both sides are built from this tree by the same compiler, so C++ types cross: the table checks
// its ABI number and the sizes of the structures it fills, so that a stale module is refused.
#include <cstddef>
#include <string>

#include "cad_model.hpp"

namespace wefm_cad {

// Raised whenever PluginApi or the structures of cad_model.hpp change.
constexpr int kPluginAbi = 1;

struct PluginApi {
  int abi = kPluginAbi;
  std::size_t sizeof_model = sizeof(CadModel);
  std::size_t sizeof_face = sizeof(CadFace);
  std::size_t sizeof_settings = sizeof(TessellationSettings);
  // load_cad_model (cad_model.hpp); never throws (anything thrown becomes `error` and false).
  bool (*load_model)(const std::string& path, const TessellationSettings& settings, CadModel& model,
                     std::string& error) = nullptr;
};

// The module's file name, and the one symbol it exports: `const PluginApi* wefm_cad_plugin(void)`.
constexpr const char* kPluginFile = "wefm-cad-occt.so";
constexpr const char* kPluginSymbol = "wefm_cad_plugin";

}  // namespace wefm_cad
