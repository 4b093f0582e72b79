// The exported table of the CAD plugin module (cad_plugin.hpp).
#include <exception>

#include "cad_plugin.hpp"

namespace {

bool load_model(const std::string& path, const wefm_cad::TessellationSettings& settings, wefm_cad::CadModel& model,
                std::string& error) {
  try {
    return wefm_cad::load_cad_model(path, settings, model, error);
  } catch (const std::exception& e) {
    error = path + ": CAD import failed: " + e.what();
  } catch (...) {
    error = path + ": CAD import failed (unknown exception)";
  }
  return false;
}

const wefm_cad::PluginApi kApi = [] {
  wefm_cad::PluginApi api;
  api.load_model = load_model;
  return api;
}();

}  // namespace

extern "C" __attribute__((visibility("default"))) const wefm_cad::PluginApi* wefm_cad_plugin() { return &kApi; }
