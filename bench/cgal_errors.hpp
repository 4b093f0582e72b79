#pragma once
// Names of CGAL's parameterization error codes, for the benchmark programs.
#include <CGAL/Surface_mesh_parameterization/Error_code.h>

namespace wefm_bench {

// CGAL 5.5's get_error_message() table lacks the ERROR_NO_TOPOLOGICAL_BALL entry, so every message
// after it is shifted by one and the last code reads past the table: name the codes here instead.
inline const char* cgal_error_name(CGAL::Surface_mesh_parameterization::Error_code e) {
  switch (e) {
    case CGAL::Surface_mesh_parameterization::OK: return "OK";
    case CGAL::Surface_mesh_parameterization::ERROR_EMPTY_MESH: return "ERROR_EMPTY_MESH";
    case CGAL::Surface_mesh_parameterization::ERROR_NON_TRIANGULAR_MESH: return "ERROR_NON_TRIANGULAR_MESH";
    case CGAL::Surface_mesh_parameterization::ERROR_NO_TOPOLOGICAL_DISC: return "ERROR_NO_TOPOLOGICAL_DISC";
    case CGAL::Surface_mesh_parameterization::ERROR_NO_TOPOLOGICAL_BALL: return "ERROR_NO_TOPOLOGICAL_BALL";
    case CGAL::Surface_mesh_parameterization::ERROR_BORDER_TOO_SHORT: return "ERROR_BORDER_TOO_SHORT";
    case CGAL::Surface_mesh_parameterization::ERROR_NON_CONVEX_BORDER: return "ERROR_NON_CONVEX_BORDER";
    case CGAL::Surface_mesh_parameterization::ERROR_CANNOT_SOLVE_LINEAR_SYSTEM: return "ERROR_CANNOT_SOLVE_LINEAR_SYSTEM";
    case CGAL::Surface_mesh_parameterization::ERROR_NO_1_TO_1_MAPPING: return "ERROR_NO_1_TO_1_MAPPING";
    case CGAL::Surface_mesh_parameterization::ERROR_WRONG_PARAMETER: return "ERROR_WRONG_PARAMETER";
  }
  return "unknown CGAL error code";
}

}  // namespace wefm_bench
