#include "summary.hpp"

#include <cmath>
#include <cstdio>

#include "names.hpp"

namespace wefm_cli {

namespace {

constexpr size_t kMaxEdgeLines = 8;  // keep the summary on one screen; the report has them all

std::string score_text(double v) {
  if (!std::isfinite(v)) return "-";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4f", v);
  return buf;
}

}  // namespace

void print_summary(const std::string& input, const FaceOutcome& o) {
  const FaceSnapshot& s = o.snap;
  const wefm_mesh_info& m = s.info;
  std::printf("wefm %s flatten %s\n", wefm_version(), input.c_str());
  std::printf("  mesh        %lld vertices, %lld triangles, %lld boundary loops, %lld merged vertices\n",
              static_cast<long long>(m.vertices), static_cast<long long>(m.triangles),
              static_cast<long long>(m.boundary_loops), static_cast<long long>(m.merged_vertices));
  size_t repeated = 0;
  for (int r : s.topology.repeated) repeated += r == 1;
  std::printf("  topology    %zu edges, %zu loops (outer %d), %zu repeated edges, %lld uses\n",
              s.topology.chains.size(), s.topology.loop_edges.size(), s.topology.outer_loop, repeated,
              static_cast<long long>(s.use_count));
  for (size_t i = 0; i < s.decisions.size() && i < kMaxEdgeLines; ++i) {
    const EdgeDecision& d = s.decisions[i];
    std::printf("  repeated    edge %d (id %lld): %-10s (%s)", d.edge, d.id, edge_mode_name(d.mode),
                d.requested == WEFM_EDGE_AUTO ? "chosen by score" : "forced");
    for (int mode = WEFM_EDGE_FREE; mode <= WEFM_EDGE_ROTATIONAL; ++mode)
      if (std::isfinite(d.scores[mode])) std::printf("  %s %s", edge_mode_name(mode), score_text(d.scores[mode]).c_str());
    std::printf("\n");
  }
  if (s.decisions.size() > kMaxEdgeLines)
    std::printf("  repeated    ... %zu more in the report\n", s.decisions.size() - kMaxEdgeLines);
  if (s.has_result) {
    const wefm_report& r = s.report;
    std::printf("  quality     score %s   flipped triangles %lld   boundary intersections %lld\n",
                score_text(r.score).c_str(), static_cast<long long>(r.flipped_triangles),
                static_cast<long long>(r.boundary_intersections));
    std::printf("  distortion  area mean %.4g max %.4g   angle mean %.4g max %.4g\n", r.area_distortion_mean,
                r.area_distortion_max, r.angle_distortion_mean, r.angle_distortion_max);
    std::printf("  solve       %s method, s %.3g reached, %s, %d steps, %d Gauss-Newton iterations", method_name(r.method), r.s,
                r.converged ? "converged" : "NOT converged", r.s_steps, r.rho_iterations);
    if (r.abandoned_steps > 0) std::printf(" (%d step%s retaken in steps of 1)", r.abandoned_steps, r.abandoned_steps == 1 ? "" : "s");
    std::printf("\n");
    std::printf("  time        %.3f s (read %.3f, solve %.3f of which factorisation %.3f, write %.3f)",
                o.time.total, o.time.read, o.time.solve, r.time_factorization, o.time.write);
    if (r.peak_memory_mb > 0) std::printf(", peak memory %.1f MB", r.peak_memory_mb);
    std::printf("\n");
  }
  for (size_t i = 0; i < o.outputs.size(); ++i)
    std::printf("  %-11s %s: %s\n", i == 0 ? "wrote" : "", o.outputs[i].first.c_str(), o.outputs[i].second.c_str());
  if (o.outputs.empty()) std::printf("  wrote       nothing\n");
}

}  // namespace wefm_cli
