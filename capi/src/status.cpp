#include <string>

#include "handles.hpp"

namespace wefm::capi {

namespace {
thread_local std::string tl_error;
}

void set_thread_error(const std::string& message) {
  try {
    tl_error = message;
  } catch (...) {
  }
}

std::string api_message(const wefm::Error& e) {
  const char* remedy = "";
  switch (e.remedy()) {
    case wefm::Remedy::none: break;
    case wefm::Remedy::set_mesh: remedy = " (wefm_face_set_mesh)"; break;
    case wefm::Remedy::solve_first: remedy = " (wefm_face_solve)"; break;
    case wefm::Remedy::add_seams: remedy = " (wefm_face_add_seams)"; break;
    case wefm::Remedy::seams_or_cut: remedy = " (seams: wefm_face_add_seams; the automatic cut: wefm_options.auto_cut)"; break;
  }
  return std::string(e.what()) + remedy;
}

wefm_status refuse_while_solving(wefm_face* face, const char* function) noexcept {
  try {
    face->last_error = std::string(function) +
                       ": the face is solving (a call from inside its own progress callback?): only wefm_face_cancel, "
                       "wefm_face_retain/release and calls that read the face are allowed until wefm_face_solve returns";
    set_thread_error(face->last_error);
  } catch (...) {
  }
  return WEFM_ERROR_INVALID_STATE;
}

wefm_status null_argument(const char* function, const char* argument) {
  set_thread_error(std::string(function) + ": argument '" + argument + "' is NULL");
  return WEFM_ERROR_NULL_ARGUMENT;
}

void check_struct_size(size_t size, const char* name) {
  if (size < sizeof(size_t))
    throw wefm::Error(wefm::Errc::invalid_argument, std::string(name) + ".struct_size is " + std::to_string(size) + ": call the matching *_init function first");
}

const char* thread_error() { return tl_error.c_str(); }

}  // namespace wefm::capi

extern "C" {

WEFM_API const char* wefm_status_string(wefm_status status) {
  switch (status) {
    case WEFM_OK: return "WEFM_OK";
    case WEFM_ERROR_NULL_ARGUMENT: return "WEFM_ERROR_NULL_ARGUMENT";
    case WEFM_ERROR_INVALID_ARGUMENT: return "WEFM_ERROR_INVALID_ARGUMENT";
    case WEFM_ERROR_OUT_OF_RANGE: return "WEFM_ERROR_OUT_OF_RANGE";
    case WEFM_ERROR_BUFFER_TOO_SMALL: return "WEFM_ERROR_BUFFER_TOO_SMALL";
    case WEFM_ERROR_INVALID_STATE: return "WEFM_ERROR_INVALID_STATE";
    case WEFM_ERROR_INVALID_MESH: return "WEFM_ERROR_INVALID_MESH";
    case WEFM_ERROR_INVALID_TOPOLOGY: return "WEFM_ERROR_INVALID_TOPOLOGY";
    case WEFM_ERROR_INVALID_CONSTRAINT: return "WEFM_ERROR_INVALID_CONSTRAINT";
    case WEFM_ERROR_SINGULAR: return "WEFM_ERROR_SINGULAR";
    case WEFM_ERROR_NOT_POSITIVE_DEFINITE: return "WEFM_ERROR_NOT_POSITIVE_DEFINITE";
    case WEFM_ERROR_NOT_CONVERGED: return "WEFM_ERROR_NOT_CONVERGED";
    case WEFM_ERROR_CANCELLED: return "WEFM_ERROR_CANCELLED";
    case WEFM_ERROR_OUT_OF_MEMORY: return "WEFM_ERROR_OUT_OF_MEMORY";
    case WEFM_ERROR_IO: return "WEFM_ERROR_IO";
    case WEFM_ERROR_UNSUPPORTED: return "WEFM_ERROR_UNSUPPORTED";
    case WEFM_ERROR_OUTSIDE_DOMAIN: return "WEFM_ERROR_OUTSIDE_DOMAIN";
    case WEFM_ERROR_INTERNAL: return "WEFM_ERROR_INTERNAL";
  }
  return "WEFM_ERROR_UNKNOWN";
}

WEFM_API const char* wefm_last_error(void) { return wefm::capi::thread_error(); }

}
