// Constraints, solving, cancellation and results.
#include <cmath>
#include <limits>

#include "handles.hpp"

using wefm::capi::Access;
using wefm::capi::on_face;

extern "C" {

WEFM_API wefm_status wefm_face_add_pin(wefm_face* face, int32_t use, double u, double v, int32_t* constraint_id) {
  WEFM_REQUIRE(face, "wefm_face_add_pin");
  return on_face(face, Access::change, "wefm_face_add_pin", [&] {
    wefm::LinearRow r;
    r.terms.emplace_back(use, wefm::Complex(1, 0));
    r.rhs = wefm::Complex(u, v);
    const wefm::Index id = face->face.add_constraint(std::move(r));
    if (constraint_id) *constraint_id = id;
  });
}

WEFM_API wefm_status wefm_face_add_constraint(wefm_face* face, int64_t n, const int32_t* uses, const double* coefficients, const double* rhs, int32_t* constraint_id) {
  WEFM_REQUIRE(face, "wefm_face_add_constraint");
  WEFM_REQUIRE(uses, "wefm_face_add_constraint");
  WEFM_REQUIRE(coefficients, "wefm_face_add_constraint");
  WEFM_REQUIRE(rhs, "wefm_face_add_constraint");
  return on_face(face, Access::change, "wefm_face_add_constraint", [&] {
    if (n < 1) throw wefm::Error(wefm::Errc::invalid_constraint, "a constraint needs at least one term (n = " + std::to_string(n) + ")");
    wefm::LinearRow r;
    for (int64_t j = 0; j < n; ++j) r.terms.emplace_back(uses[j], wefm::Complex(coefficients[2 * j], coefficients[2 * j + 1]));
    r.rhs = wefm::Complex(rhs[0], rhs[1]);
    const wefm::Index id = face->face.add_constraint(std::move(r));
    if (constraint_id) *constraint_id = id;
  });
}

WEFM_API wefm_status wefm_face_clear_constraints(wefm_face* face) {
  WEFM_REQUIRE(face, "wefm_face_clear_constraints");
  return on_face(face, Access::change, "wefm_face_clear_constraints", [&] { face->face.clear_constraints(); });
}

WEFM_API wefm_status wefm_face_set_progress_callback(wefm_face* face, wefm_progress_fn fn, void* user_data) {
  WEFM_REQUIRE(face, "wefm_face_set_progress_callback");
  return on_face(face, Access::change, "wefm_face_set_progress_callback", [&] {
    face->progress = fn;
    face->progress_user = user_data;
  });
}

WEFM_API wefm_status wefm_face_solve(wefm_face* face) {
  WEFM_REQUIRE(face, "wefm_face_solve");
  const wefm_status status = on_face(face, Access::change, "wefm_face_solve", [&] {
    face->cancel.store(false);
    const wefm::capi::BusyFace busy(face);
    face->face.solve(wefm::capi::progress_of(face), &face->cancel);
  });
  wefm::capi::free_if_released(face);
  return status;
}

WEFM_API wefm_status wefm_face_cancel(wefm_face* face) {
  WEFM_REQUIRE(face, "wefm_face_cancel");
  face->cancel.store(true);
  return WEFM_OK;
}

WEFM_API wefm_status wefm_face_has_result(const wefm_face* face, int32_t* solved) {
  WEFM_REQUIRE(face, "wefm_face_has_result");
  WEFM_REQUIRE(solved, "wefm_face_has_result");
  *solved = face->face.has_result() ? 1 : 0;
  return WEFM_OK;
}

WEFM_API wefm_status wefm_face_get_uv(wefm_face* face, double* uv, int64_t capacity, int64_t* count) {
  WEFM_REQUIRE(face, "wefm_face_get_uv");
  WEFM_REQUIRE(count, "wefm_face_get_uv");
  return on_face(face, Access::read, "wefm_face_get_uv", [&] {
    const wefm::VectorXc& z = face->face.result().uv;
    wefm::capi::copy_out_records(static_cast<std::size_t>(z.size()), 2, uv, capacity, count, [&](std::size_t u, double* out) {
      out[0] = z[static_cast<wefm::Index>(u)].real();
      out[1] = z[static_cast<wefm::Index>(u)].imag();
    });
  });
}

WEFM_API wefm_status wefm_face_get_edge_modes(wefm_face* face, int32_t* modes, int64_t capacity, int64_t* count) {
  WEFM_REQUIRE(face, "wefm_face_get_edge_modes");
  WEFM_REQUIRE(count, "wefm_face_get_edge_modes");
  return on_face(face, Access::read, "wefm_face_get_edge_modes", [&] {
    std::vector<int32_t> v;
    for (wefm::EdgeMode m : face->face.result().edge_modes) v.push_back(static_cast<int32_t>(m));
    wefm::capi::copy_out(v, modes, capacity, count);
  });
}

WEFM_API wefm_status wefm_face_get_edge_scores(wefm_face* face, int32_t edge, double* scores, int64_t capacity, int64_t* count) {
  WEFM_REQUIRE(face, "wefm_face_get_edge_scores");
  WEFM_REQUIRE(count, "wefm_face_get_edge_scores");
  return on_face(face, Access::read, "wefm_face_get_edge_scores", [&] {
    const auto& all = face->face.result().edge_scores;
    if (edge < 0 || static_cast<size_t>(edge) >= all.size())
      throw wefm::Error(wefm::Errc::out_of_range, "edge " + std::to_string(edge) + " does not exist (" + std::to_string(all.size()) + " edges)");
    const auto& s = all[static_cast<size_t>(edge)];
    wefm::capi::copy_out(std::vector<double>(s.begin(), s.end()), scores, capacity, count);
  });
}

WEFM_API wefm_status wefm_face_get_report(const wefm_face* face, wefm_report* report) {
  WEFM_REQUIRE(face, "wefm_face_get_report");
  WEFM_REQUIRE(report, "wefm_face_get_report");
  return on_face(const_cast<wefm_face*>(face), Access::read, "wefm_face_get_report", [&] {
    wefm::capi::check_struct_size(report->struct_size, "wefm_report");
    const wefm::SolveReport& s = face->face.result().report;
    wefm_report r{};
    r.struct_size = sizeof(r);
    r.score = s.quality.score;
    r.flipped_triangles = s.quality.flips;
    r.boundary_intersections = s.quality.boundary_intersections;
    r.area_distortion_mean = s.quality.area_mean;
    r.area_distortion_max = s.quality.area_max;
    r.angle_distortion_mean = s.quality.angle_mean;
    r.angle_distortion_max = s.quality.angle_max;
    r.uv_area = s.quality.uv_area;
    r.area_3d = s.quality.area_3d;
    r.s = s.s;
    r.converged = s.converged ? 1 : 0;
    r.method = static_cast<int32_t>(s.method);
    r.s_steps = s.s_steps;
    r.rho_iterations = s.rho_iterations;
    r.rho_change = s.rho_change;
    r.symbolic_analyses = s.counters.analyses;
    r.numeric_factorizations = s.counters.factorizations;
    r.solves = s.counters.solves;
    r.iterative_iterations = s.iterative_iterations;
    r.auto_cut = s.auto_cut ? 1 : 0;
    r.degenerate_triangles = s.degenerate_triangles;
    r.min_beta_raised = s.min_beta_raised ? 1 : 0;
    r.boundary_unwind = s.unwind;
    r.auto_cut_edges = s.auto_cut_edges;
    r.auto_cut_uncut_kept = s.auto_cut_uncut_kept ? 1 : 0;
    r.auto_cut_length = s.auto_cut_length;
    r.auto_cut_other_score = s.auto_cut_other_score;
    r.via_s = s.via_s;
    r.boundary_unwind_weight = s.unwind_weight;
    r.abandoned_steps = s.abandoned_steps;
    r.time_topology = s.time.topology;
    r.time_coefficients = s.time.coefficients;
    r.time_assembly = s.time.assembly;
    r.time_analysis = s.time.analysis;
    r.time_factorization = s.time.factorization;
    r.time_solve = s.time.solve;
    r.time_continuation = s.time.continuation;
    r.time_quality = s.time.quality;
    r.time_total = s.time.total;
    r.peak_memory_mb = s.peak_memory_mb;
    wefm::capi::write_versioned(report, r);
  });
}

WEFM_API wefm_status wefm_face_get_step_history(const wefm_face* face, double* steps, int64_t capacity, int64_t* count) {
  WEFM_REQUIRE(face, "wefm_face_get_step_history");
  WEFM_REQUIRE(count, "wefm_face_get_step_history");
  return on_face(const_cast<wefm_face*>(face), Access::read, "wefm_face_get_step_history", [&] {
    std::vector<double> v;
    for (const wefm::StepInfo& s : face->face.result().steps) v.insert(v.end(), {s.s, static_cast<double>(s.iterations), s.rho_change});
    wefm::capi::copy_out(v, steps, capacity, count);
  });
}

WEFM_API wefm_status wefm_face_write_obj(wefm_face* face, const char* path) {
  WEFM_REQUIRE(face, "wefm_face_write_obj");
  WEFM_REQUIRE(path, "wefm_face_write_obj");
  return on_face(face, Access::read, "wefm_face_write_obj", [&] {
    const wefm::FlattenResult& r = face->face.result();
    wefm::write_obj_uv(path, face->face.mesh(), face->face.topology(), r.uv);
  });
}

}
