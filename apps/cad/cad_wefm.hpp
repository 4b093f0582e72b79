#pragma once
// An imported face handed to the library through the public C API only: the triangulation
// (wefm_face_set_mesh), every edge (wefm_face_add_edge, in CadFace::edges order, so library edge k is
// face.edges[k]), the loops (wefm_face_add_loop) and the outer loop.
#include <string>

#include "cad_model.hpp"
#include "wefm/wefm.h"

namespace wefm_cad {

// Returns the first failing status with a message naming the edge (by model id) or loop at fault.
wefm_status set_face_from_cad(wefm_face* handle, const CadFace& face, std::string& error);

}  // namespace wefm_cad
