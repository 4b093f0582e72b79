#pragma once
// An imported face as files: the triangulation as OBJ and its topology in the topo.json schema of the
// sample data (apps/README.md, "Topology file"), so `wefm flatten face.obj --topology topo.json`
// reproduces any face of a model on its own.
#include <string>

#include "cad_model.hpp"

namespace wefm_cad {

// Both return false + message when the file cannot be written.
bool write_face_obj(const std::string& path, const CadFace& face, const std::string& model_path, std::string& error);
bool write_face_topology(const std::string& path, const CadFace& face, const std::string& model_path,
                         std::string& error);

}  // namespace wefm_cad
