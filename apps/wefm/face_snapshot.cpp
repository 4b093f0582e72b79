#include "face_snapshot.hpp"

#include <cmath>

#include "size_query.hpp"

namespace wefm_cli {

wefm_status snapshot_topology(wefm_face* face, const std::vector<long long>& ids, FaceSnapshot& snap) {
  TopologyFile& t = snap.topology;
  t = TopologyFile{};
  int64_t edges = 0, loops = 0;
  wefm_status st = wefm_face_edge_count(face, &edges);
  if (st == WEFM_OK) st = wefm_face_loop_count(face, &loops);
  if (st == WEFM_OK) st = wefm_face_use_count(face, &snap.use_count);
  if (st != WEFM_OK) return st;
  // File ids only when the library kept the file's edges one-to-one (it does when loops were given).
  const bool use_ids = static_cast<int64_t>(ids.size()) == edges;
  for (int32_t e = 0; e < edges; ++e) {
    std::vector<int32_t> chain;
    st = fetch(chain, [&](int32_t* b, int64_t c, int64_t* n) { return wefm_face_get_edge(face, e, b, c, n); });
    if (st != WEFM_OK) return st;
    int32_t rep = 0;
    if ((st = wefm_face_edge_is_repeated(face, e, &rep)) != WEFM_OK) return st;
    t.ids.push_back(use_ids ? ids[static_cast<size_t>(e)] : e);
    t.chains.push_back(std::move(chain));
    t.repeated.push_back(rep ? 1 : 0);
    t.modes.push_back(-1);
  }
  snap.loop_uses.clear();
  for (int32_t l = 0; l < loops; ++l) {
    std::vector<int32_t> pairs, uses;
    st = fetch(pairs, [&](int32_t* b, int64_t c, int64_t* n) { return wefm_face_get_loop(face, l, b, c, n); });
    if (st == WEFM_OK)
      st = fetch(uses, [&](int32_t* b, int64_t c, int64_t* n) { return wefm_face_get_loop_uses(face, l, b, c, n); });
    if (st != WEFM_OK) return st;
    std::vector<int32_t> es, rs;
    for (size_t j = 0; j + 1 < pairs.size(); j += 2) {
      es.push_back(pairs[j]);
      rs.push_back(pairs[j + 1] ? 1 : 0);
    }
    t.loop_edges.push_back(std::move(es));
    t.loop_reversed.push_back(std::move(rs));
    snap.loop_uses.push_back(std::move(uses));
  }
  int32_t outer = -1;
  if ((st = wefm_face_outer_loop(face, &outer)) != WEFM_OK) return st;
  t.outer_loop = outer;
  return WEFM_OK;
}

wefm_status snapshot_result(wefm_face* face, const std::vector<int>& requested, int default_mode,
                            FaceSnapshot& snap) {
  int32_t solved = 0;
  wefm_status st = wefm_face_has_result(face, &solved);
  if (st != WEFM_OK) return st;
  snap.has_result = solved != 0;
  if (!snap.has_result) return WEFM_OK;
  auto use_vertices = [&](int32_t* b, int64_t c, int64_t* n) { return wefm_face_get_use_vertices(face, b, c, n); };
  auto tri_uses = [&](int32_t* b, int64_t c, int64_t* n) { return wefm_face_get_triangle_uses(face, b, c, n); };
  auto uv = [&](double* b, int64_t c, int64_t* n) { return wefm_face_get_uv(face, b, c, n); };
  auto steps = [&](double* b, int64_t c, int64_t* n) { return wefm_face_get_step_history(face, b, c, n); };
  std::vector<int32_t> modes;
  auto get_modes = [&](int32_t* b, int64_t c, int64_t* n) { return wefm_face_get_edge_modes(face, b, c, n); };
  if ((st = fetch(snap.use_vertex, use_vertices)) != WEFM_OK || (st = fetch(snap.tri_uses, tri_uses)) != WEFM_OK ||
      (st = fetch(snap.uv, uv)) != WEFM_OK || (st = fetch(snap.steps, steps)) != WEFM_OK ||
      (st = fetch(modes, get_modes)) != WEFM_OK)
    return st;
  wefm_report_init(&snap.report);
  if ((st = wefm_face_get_report(face, &snap.report)) != WEFM_OK) return st;
  TopologyFile& t = snap.topology;
  snap.decisions.clear();
  for (size_t e = 0; e < t.chains.size(); ++e) {
    t.modes[e] = e < modes.size() ? modes[e] : -1;
    if (t.repeated[e] != 1) continue;
    EdgeDecision d;
    d.edge = static_cast<int32_t>(e);
    d.id = t.ids[e];
    d.mode = t.modes[e];
    d.requested = e < requested.size() && requested[e] >= 0 ? requested[e] : default_mode;
    d.scores.fill(std::nan(""));
    int64_t n = 0;
    if (wefm_face_get_edge_scores(face, d.edge, d.scores.data(), 5, &n) != WEFM_OK) d.scores.fill(std::nan(""));
    snap.decisions.push_back(d);
  }
  return WEFM_OK;
}

}  // namespace wefm_cli
