// libFuzzer target: the CAD plugin's import (apps/cad: Open CASCADE reading, tessellation, face
// import) on mutated STEP, IGES and BREP files, in process. The first byte picks the format, the
// rest is the file. Open CASCADE itself is not instrumented, so the search is guided by our own code
// only; run with a per-input time limit (-timeout) and a modest -max_len (scripts: README.md in
// tests/fuzz), since the tool bounds a real import with a killed child process, not in process.
// Properties: a failure has a message; a model that imports has faces whose triangles, edge chains,
// loops and outer loop index what is there; it survives the byte form the import child hands back
// (cad_model_wire) unchanged; and those decoded bytes, cut short, are refused, not read past.
#include <string>
#include <vector>

#include "cad_model.hpp"
#include "cad_model_wire.hpp"
#include "fuzz_files.hpp"

using wefm_fuzz::violated;

namespace {

const char* const kExtensions[] = {".step", ".iges", ".brep"};

void check_face(const wefm_cad::CadFace& f) {
  if (!f.error.empty()) return;  // not imported: only its reason is used
  const int64_t nv = static_cast<int64_t>(f.xyz.size() / 3);
  if (f.xyz.size() % 3 || f.triangles.size() % 3) violated("import", "coordinates or triangles not in threes");
  for (int32_t v : f.triangles)
    if (v < 0 || v >= nv) violated("import", "a triangle names a vertex that is not there");
  for (const auto& e : f.edges)
    for (int32_t v : e.vertices)
      if (v < 0 || v >= nv) violated("import", "an edge chain names a vertex that is not there");
  for (const auto& loop : f.loops)
    for (const auto& u : loop)
      if (u.edge < 0 || static_cast<size_t>(u.edge) >= f.edges.size()) violated("import", "a loop names a missing edge");
  if (f.outer_loop < -1 || f.outer_loop >= static_cast<int>(f.loops.size())) violated("import", "outer loop out of range");
}

void check_wire(const wefm_cad::CadModel& m) {
  const std::string bytes = wefm_cad::encode_cad_model(m);
  wefm_cad::CadModel back;
  if (!wefm_cad::decode_cad_model(bytes, back)) violated("cad_model_wire", "a model's own bytes are refused");
  if (wefm_cad::encode_cad_model(back) != bytes) violated("cad_model_wire", "the decoded model encodes differently");
  for (size_t cut : {bytes.size() / 2, bytes.size() - 1})
    if (wefm_cad::decode_cad_model(std::string_view(bytes).substr(0, cut), back))
      violated("cad_model_wire", "truncated bytes were accepted");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  // The raw bytes as the child's answer: any garbage must be refused or decoded, never read past.
  wefm_cad::CadModel garbage;
  (void)wefm_cad::decode_cad_model(std::string_view(reinterpret_cast<const char*>(data), size), garbage);

  const std::string path = wefm_fuzz::write_temp_file(std::string("model") + kExtensions[data[0] % 3], data + 1, size - 1);
  wefm_cad::TessellationSettings coarse;  // few triangles: the time goes to reading, not meshing
  coarse.relative_deflection = 0.05;
  coarse.angular_deflection = 1.0;
  wefm_cad::CadModel model;
  std::string error;
  bool ok = false;
  try {
    ok = wefm_cad::load_cad_model(path, coarse, model, error);
  } catch (...) {
    return 0;  // the plugin's entry (cad_plugin_entry.cpp) turns this into an error message
  }
  if (!ok) {
    if (error.empty()) violated("load_cad_model", "a failure without a message");
    return 0;
  }
  for (const auto& face : model.faces) check_face(face);
  check_wire(model);
  return 0;
}
