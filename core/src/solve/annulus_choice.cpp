#include "wefm/core/solve/annulus_choice.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "wefm/core/sys/error.hpp"

namespace wefm {

void keep_uncut_if_better(const TriMesh& mesh, const TopologySpec& uncut_spec, const Topology& cut, const FlattenInput& cut_in,
                          FlattenResult& cut_res) {
  Topology plain;
  try {
    plain = build_topology(mesh, uncut_spec);
  } catch (const Error&) {
    return;  // the cut topology is valid; an uncut one that is not has nothing to offer
  }
  // Both topologies number the same corners: a cut use maps to the uncut use of any of its corners.
  std::vector<Index> to_plain(static_cast<size_t>(cut.use_count), -1);
  for (size_t c = 0; c < cut.corner_use.size(); ++c) to_plain[static_cast<size_t>(cut.corner_use[c])] = plain.corner_use[c];
  FlattenInput in = cut_in;
  in.topo = &plain;
  in.edge_modes.clear();  // they name the cut topology's edges; the uncut face has no repeated edge
  for (LinearRow& r : in.constraints) {
    std::map<Index, Complex> acc;  // both sides of the seam in one row become one use
    for (const auto& [u, g] : r.terms) acc[to_plain[static_cast<size_t>(u)]] += g;
    r.terms.clear();
    for (const auto& [u, g] : acc)
      if (g != Complex(0, 0)) r.terms.emplace_back(u, g);
    if (r.terms.empty()) return;  // a row across the seam only: it has no uncut meaning
  }
  // Probe the uncut face conformally first (one factorisation) against the cut's conformal score;
  // only an uncut layout that wins there gets the full solve: the uncut continuation is costly when
  // it fails to converge (the real cylinder sample: 50 Gauss-Newton iterations, 20x the cut solve).
  SolveReport& rep = cut_res.report;
  double cut_conformal = -std::numeric_limits<double>::infinity();
  for (const RepeatedEdge& r : cut.repeated)
    for (double sc : cut_res.edge_scores[static_cast<size_t>(r.edge)])
      if (std::isfinite(sc)) cut_conformal = std::max(cut_conformal, sc);
  if (!std::isfinite(cut_conformal)) cut_conformal = rep.quality.score;  // modes forced: no conformal score kept
  auto attempt = [&](const FlattenInput& fi, FlattenResult& out) {
    try {
      out = flatten(fi);
      return true;
    } catch (const Error& e) {
      if (e.code() == Errc::cancelled) throw;
      return false;
    }
  };
  FlattenResult alt;
  if (in.options.s > 0) {
    FlattenInput probe = in;
    probe.options.s = 0;
    if (!attempt(probe, alt)) return;
    rep.time.total += alt.report.time.total;
    if (!(alt.report.quality.score > cut_conformal + 1e-9)) {
      rep.auto_cut_other_score = alt.report.quality.score;
      return;
    }
  }
  if (!attempt(in, alt)) return;
  // Ties keep the cut: its periodic domain is what a mesher wants (matching nodes across the seam);
  // an unconverged uncut layout does not replace a converged cut one.
  if (!(alt.report.quality.score > rep.quality.score + 1e-9) || (rep.converged && !alt.report.converged)) {
    rep.auto_cut_other_score = alt.report.quality.score;
    rep.time.total += alt.report.time.total;
    return;
  }
  FlattenResult out;
  out.uv.resize(cut.use_count);
  for (Index u = 0; u < cut.use_count; ++u) out.uv[u] = alt.uv[to_plain[static_cast<size_t>(u)]];
  out.edge_modes = cut_res.edge_modes;
  for (const RepeatedEdge& r : cut.repeated) out.edge_modes[static_cast<size_t>(r.edge)] = EdgeMode::Scar;
  out.edge_scores = cut_res.edge_scores;
  out.steps = alt.steps;
  out.report = alt.report;
  SolveReport& o = out.report;
  o.quality = evaluate_quality(mesh, cut, out.uv);  // on the returned uses: the cut's loop included
  o.auto_cut = true;
  o.auto_cut_edges = rep.auto_cut_edges;
  o.auto_cut_length = rep.auto_cut_length;
  o.auto_cut_uncut_kept = true;
  o.auto_cut_other_score = rep.quality.score;
  o.time.total += rep.time.total;
  o.counters.analyses += rep.counters.analyses;
  o.counters.factorizations += rep.counters.factorizations;
  o.counters.solves += rep.counters.solves;
  cut_res = std::move(out);
}

}  // namespace wefm
