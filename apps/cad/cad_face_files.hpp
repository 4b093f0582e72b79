#pragma once
// An imported face as files: the triangulation as OBJ and its topology in the topo.json schema of the
// sample data (apps/README.md, "Topology file"), so `wefm flatten face.obj --topology topo.json`
// reproduces any face of a model on its own.
#include <string>

#include "cad_model.hpp"

namespace wefm_cad {

// The files' text; the tool writes it with its atomic output (apps/wefm/output_file.hpp).
std::string face_obj_text(const CadFace& face, const std::string& model_path);
std::string face_topology_text(const CadFace& face, const std::string& model_path);

}  // namespace wefm_cad
