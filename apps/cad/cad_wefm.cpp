#include "cad_wefm.hpp"

namespace wefm_cad {

wefm_status set_face_from_cad(wefm_face* handle, const CadFace& face, std::string& error) {
  if (!face.error.empty()) {
    error = face.error;
    return WEFM_ERROR_INVALID_ARGUMENT;
  }
  wefm_status st = wefm_face_set_mesh(handle, static_cast<int64_t>(face.xyz.size() / 3), face.xyz.data(),
                                      static_cast<int64_t>(face.triangles.size() / 3), face.triangles.data());
  if (st != WEFM_OK) {
    error = std::string("mesh: ") + wefm_face_last_error(handle);
    return st;
  }
  for (const CadEdge& e : face.edges) {
    int32_t id = -1;
    st = wefm_face_add_edge(handle, static_cast<int64_t>(e.vertices.size()), e.vertices.data(), &id);
    if (st != WEFM_OK) {
      error = "edge id " + std::to_string(e.id) + ": " + wefm_face_last_error(handle);
      return st;
    }
  }
  for (size_t l = 0; l < face.loops.size(); ++l) {
    std::vector<int32_t> edges, reversed;
    for (const CadEdgeUse& u : face.loops[l]) {
      edges.push_back(u.edge);
      reversed.push_back(u.reversed ? 1 : 0);
    }
    int32_t id = -1;
    st = wefm_face_add_loop(handle, static_cast<int64_t>(edges.size()), edges.data(), reversed.data(), &id);
    if (st != WEFM_OK) {
      error = "loop " + std::to_string(l) + ": " + wefm_face_last_error(handle);
      return st;
    }
  }
  if (face.outer_loop >= 0 && (st = wefm_face_set_outer_loop(handle, face.outer_loop)) != WEFM_OK) {
    error = std::string("outer loop: ") + wefm_face_last_error(handle);
    return st;
  }
  return WEFM_OK;
}

}  // namespace wefm_cad
