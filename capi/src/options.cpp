// Defaults live in wefm::Options (core); the C structs are filled from it so the two never drift.
#include <cstring>
#include <string>

#include "options_convert.hpp"

using wefm::capi::guarded;

namespace wefm::capi {

wefm_options to_c(const wefm::Options& o) {
  wefm_options c{};
  c.struct_size = sizeof(wefm_options);
  c.s = o.s;
  c.k = o.k;
  c.boundary_weight = o.boundary_weight;
  c.curvature_adjust = o.curvature_adjust ? 1 : 0;
  c.method = static_cast<int>(o.method);
  c.solver = o.backend == Backend::Cholmod ? WEFM_SOLVER_CHOLMOD : o.backend == Backend::Eigen ? WEFM_SOLVER_EIGEN : WEFM_SOLVER_AUTO;
  c.default_edge_mode = static_cast<int>(o.default_edge_mode);
  c.s_step = o.s_step;
  c.rho_tolerance = o.rho_tolerance;
  c.max_rho_iterations = o.max_rho_iterations;
  c.rollout_tolerance = o.rollout_tolerance;
  c.max_rollout_sweeps = o.max_rollout_sweeps;
  c.score_threshold = o.score_threshold;
  c.auto_cut = o.auto_cut ? 1 : 0;
  c.threads = o.threads;
  c.memory_limit_mb = o.memory_limit_mb;
  c.min_beta = o.min_beta;
  c.residual = static_cast<int>(o.residual);
  return c;
}

wefm::Options from_c(const wefm_options& c) {
  wefm::Options o;
  o.s = c.s;
  o.k = c.k;
  o.boundary_weight = c.boundary_weight;
  o.curvature_adjust = c.curvature_adjust != 0;
  if (c.method != WEFM_METHOD_GLOBAL && c.method != WEFM_METHOD_ROLLOUT) throw Error(Errc::invalid_argument, "option method = " + std::to_string(c.method) + " is not a wefm_method");
  o.method = static_cast<Method>(c.method);
  switch (c.solver) {
    case WEFM_SOLVER_AUTO: o.backend = Backend::Auto; break;
    case WEFM_SOLVER_CHOLMOD: o.backend = Backend::Cholmod; break;
    case WEFM_SOLVER_EIGEN: o.backend = Backend::Eigen; break;
    default: throw Error(Errc::invalid_argument, "option solver = " + std::to_string(c.solver) + " is not a wefm_solver");
  }
  if (c.solver == WEFM_SOLVER_CHOLMOD && !have_cholmod()) throw Error(Errc::unsupported, "option solver = WEFM_SOLVER_CHOLMOD, but this build has no SuiteSparse");
  if (c.default_edge_mode < 0 || c.default_edge_mode > 4) throw Error(Errc::invalid_argument, "option default_edge_mode = " + std::to_string(c.default_edge_mode) + " is not a wefm_edge_mode");
  o.default_edge_mode = static_cast<EdgeMode>(c.default_edge_mode);
  o.s_step = c.s_step;
  o.rho_tolerance = c.rho_tolerance;
  o.max_rho_iterations = c.max_rho_iterations;
  o.rollout_tolerance = c.rollout_tolerance;
  o.max_rollout_sweeps = c.max_rollout_sweeps;
  o.score_threshold = c.score_threshold;
  o.auto_cut = c.auto_cut != 0;
  o.threads = c.threads;
  o.memory_limit_mb = c.memory_limit_mb;
  o.min_beta = c.min_beta;
  if (c.residual != WEFM_RESIDUAL_PER_HALF_EDGE && c.residual != WEFM_RESIDUAL_PER_USE)
    throw Error(Errc::invalid_argument, "option residual = " + std::to_string(c.residual) + " is not a wefm_residual");
  o.residual = static_cast<Residual>(c.residual);
  validate_options(o);
  return o;
}

}  // namespace wefm::capi

namespace {

// The *_init protocol of wefm.h ("ABI"): `size` is the caller's sizeof, which may be smaller (older
// header) or larger (newer header) than ours. Write our defaults into the bytes both know, zero the
// bytes only the caller knows, and never touch anything past `size`.
template <class T>
wefm_status init_versioned(T* out, size_t size, const char* function, const T& defaults) noexcept {
  if (!out) return wefm::capi::null_argument(function, "struct");
  return guarded(nullptr, [&] {
    if (size < sizeof(size_t))
      throw wefm::Error(wefm::Errc::invalid_argument, std::string(function) + ": struct_size " + std::to_string(size) + " cannot even hold the struct_size field; pass sizeof(struct)");
    unsigned char* bytes = reinterpret_cast<unsigned char*>(out);
    const size_t known = size < sizeof(T) ? size : sizeof(T);
    std::memcpy(bytes, &defaults, known);
    if (size > known) std::memset(bytes + known, 0, size - known);
    std::memcpy(bytes, &size, sizeof(size_t));  // struct_size is the first member of every versioned struct
  });
}

template <class T>
T zeroed() {
  T t{};
  t.struct_size = sizeof(T);
  return t;
}

}  // namespace

extern "C" {

WEFM_API wefm_status wefm_options_init(wefm_options* options, size_t struct_size) {
  wefm_options defaults{};
  const wefm_status st = guarded(nullptr, [&] { defaults = wefm::capi::to_c(wefm::Options{}); });
  return st != WEFM_OK ? st : init_versioned(options, struct_size, "wefm_options_init", defaults);
}

WEFM_API wefm_status wefm_report_init(wefm_report* report, size_t struct_size) {
  return init_versioned(report, struct_size, "wefm_report_init", zeroed<wefm_report>());
}

WEFM_API wefm_status wefm_mesh_info_init(wefm_mesh_info* info, size_t struct_size) {
  return init_versioned(info, struct_size, "wefm_mesh_info_init", zeroed<wefm_mesh_info>());
}

WEFM_API wefm_status wefm_mesh_options_init(wefm_mesh_options* options, size_t struct_size) {
  wefm_mesh_options o = zeroed<wefm_mesh_options>();
  o.type = WEFM_MESH_FREE;
  o.size = 0;
  for (int j = 0; j < 4; ++j) o.corners[j] = -1;
  o.quads = 1;
  o.smoothing_iterations = 5;
  o.corner_angle_deg = 30;
  o.min_angle_deg = 28;
  o.max_elements = 0;
  o.elements = WEFM_ELEMENTS_TRIANGLES;
  o.split_chords = 0;
  return init_versioned(options, struct_size, "wefm_mesh_options_init", o);
}

WEFM_API wefm_status wefm_mesh_report_init(wefm_mesh_report* report, size_t struct_size) {
  return init_versioned(report, struct_size, "wefm_mesh_report_init", zeroed<wefm_mesh_report>());
}

}
