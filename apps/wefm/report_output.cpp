#include "report_output.hpp"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <nlohmann/json.hpp>

#include "exit_codes.hpp"
#include "output_file.hpp"
#include "huge_page_malloc.hpp"
#include "names.hpp"

namespace wefm_cli {

namespace {

using Json = nlohmann::ordered_json;

// JSON has no NaN/inf: an untried score or an unknown value is null.
Json number(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

std::string key_of(const std::string& what) {
  std::string k = what;
  for (char& c : k)
    if (c == ' ') c = '_';
  return k;
}

}  // namespace

int write_report_json(const std::string& path, const ReportContext& ctx, const FaceSnapshot& snap, std::string& error) {
  const wefm_report& r = snap.report;
  const wefm_mesh_info& m = snap.info;
  Json j;
  j["wefm_version"] = wefm_version();
  j["input"] = ctx.input;
  j["status"] = ctx.exit_code == kExitOk ? "ok" : ctx.exit_code == kExitSolver ? "not_converged" : "failed";
  j["exit_code"] = ctx.exit_code;
  j["message"] = ctx.message;
  j["warnings"] = ctx.warnings;
  j["mesh"] = {{"vertices", m.vertices},
               {"triangles", m.triangles},
               {"merged_vertices", m.merged_vertices},
               {"boundary_loops", m.boundary_loops},
               {"genus", m.genus},
               {"degenerate_triangles", m.degenerate_triangles}};
  int64_t repeated = 0;
  for (int rep : snap.topology.repeated) repeated += rep == 1;
  j["topology"] = {{"edges", snap.topology.chains.size()},
                   {"loops", snap.topology.loop_edges.size()},
                   {"outer_loop", snap.topology.outer_loop},
                   {"repeated_edges", repeated},
                   {"uses", snap.use_count}};
  j["score"] = number(r.score);
  j["flipped_triangles"] = r.flipped_triangles;
  j["boundary_intersections"] = r.boundary_intersections;
  j["area_distortion_mean"] = number(r.area_distortion_mean);
  j["area_distortion_max"] = number(r.area_distortion_max);
  j["angle_distortion_mean"] = number(r.angle_distortion_mean);
  j["angle_distortion_max"] = number(r.angle_distortion_max);
  j["uv_area"] = number(r.uv_area);
  j["area_3d"] = number(r.area_3d);
  j["s"] = number(r.s);
  j["converged"] = r.converged != 0;
  j["method"] = method_name(r.method);
  j["auto_cut"] = r.auto_cut != 0;
  if (r.auto_cut) {
    j["auto_cut_edges"] = r.auto_cut_edges;
    j["auto_cut_length"] = number(r.auto_cut_length);
    j["auto_cut_uncut_kept"] = r.auto_cut_uncut_kept != 0;
    j["auto_cut_other_score"] = number(r.auto_cut_other_score);
  }
  j["regularised_triangles"] = r.degenerate_triangles;
  j["min_beta_raised"] = r.min_beta_raised != 0;
  j["boundary_unwind"] = number(r.boundary_unwind);
  j["boundary_unwind_weight"] = number(r.boundary_unwind_weight);
  j["via_s"] = number(r.via_s);
  Json decisions = Json::array();
  for (const auto& d : snap.decisions) {
    Json scores;
    for (int mode = WEFM_EDGE_FREE; mode <= WEFM_EDGE_ROTATIONAL; ++mode) scores[edge_mode_name(mode)] = number(d.scores[mode]);
    decisions.push_back({{"edge", d.edge},
                         {"id", d.id},
                         {"mode", edge_mode_name(d.mode)},
                         {"requested", edge_mode_name(d.requested)},
                         {"scores", scores}});
  }
  j["edge_decisions"] = decisions;
  Json steps = Json::array();
  for (size_t k = 0; k + 2 < snap.steps.size(); k += 3)
    steps.push_back({{"s", number(snap.steps[k])},
                     {"rho_iterations", static_cast<int64_t>(snap.steps[k + 1])},
                     {"rho_change", number(snap.steps[k + 2])}});
  j["iterations"] = {{"s_steps", r.s_steps},
                     {"rho_iterations", r.rho_iterations},
                     {"rho_change", number(r.rho_change)},
                     {"iterative_iterations", r.iterative_iterations},
                     {"abandoned_steps", r.abandoned_steps},
                     {"steps", steps}};
  j["counters"] = {{"symbolic_analyses", r.symbolic_analyses},
                   {"numeric_factorizations", r.numeric_factorizations},
                   {"solves", r.solves}};
  j["timings"] = {{"topology", number(r.time_topology)},
                  {"coefficients", number(r.time_coefficients)},
                  {"assembly", number(r.time_assembly)},
                  {"analysis", number(r.time_analysis)},
                  {"factorization", number(r.time_factorization)},
                  {"solve", number(r.time_solve)},
                  {"continuation", number(r.time_continuation)},
                  {"quality", number(r.time_quality)},
                  {"total", number(r.time_total)},
                  {"read_input", number(ctx.timings.read)},
                  {"setup", number(ctx.timings.setup)},
                  {"wall_solve", number(ctx.timings.solve)},
                  {"wall_before_report", number(ctx.timings.total)}};
  j["peak_memory_mb"] = number(r.peak_memory_mb);
  j["huge_page_malloc"] = huge_page_malloc_active();
  j["threads"] = ctx.threads > 1 ? ctx.threads : 1;
  Json outputs = Json::object();
  for (const auto& [what, p] : ctx.outputs) outputs[key_of(what)] = p;
  j["outputs"] = outputs;

  return write_file_atomically(path, j.dump(2) + '\n', error);
}

}  // namespace wefm_cli
