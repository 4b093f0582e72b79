#pragma once
// An imported face's topology in the topo.json schema of the sample data (apps/README.md, "Topology
// file"): with the face's triangulation as OBJ (written by the tool's mesh writer, mesh_formats.hpp),
// `wefm flatten face.obj --topology topo.json` reproduces any face of a model on its own.
#include <string>

#include "cad_model.hpp"

namespace wefm_cad {

// The file's text; the tool writes it with its atomic output (apps/wefm/output_file.hpp).
std::string face_topology_text(const CadFace& face, const std::string& model_path);

}  // namespace wefm_cad
