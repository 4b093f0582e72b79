#include "mapped_tubes.hpp"

#include <algorithm>
#include <cmath>

namespace wefm_cli {

namespace {

// A face that is a tube: one loop, a seam used twice, and between its two uses the two ends (each a
// chain of edges: a circle, or arcs).
struct Tube {
  const wefm_cad::CadEdge* seam = nullptr;
  std::vector<const wefm_cad::CadEdge*> ends[2];
};

bool tube_of(const wefm_cad::CadFace& f, Tube& t) {
  if (!f.error.empty() || f.loops.size() != 1) return false;
  const auto& loop = f.loops[0];
  std::vector<size_t> seam_at;
  for (size_t k = 0; k < loop.size(); ++k) {
    const wefm_cad::CadEdge& e = f.edges[static_cast<size_t>(loop[k].edge)];
    if (e.degenerated || e.vertices.size() < 2) return false;
    if (!e.seam) continue;
    if (t.seam && t.seam != &e) return false;
    t.seam = &e;
    seam_at.push_back(k);
  }
  if (seam_at.size() != 2) return false;
  for (size_t side = 0; side < 2; ++side)
    for (size_t k = (seam_at[side] + 1) % loop.size(); k != seam_at[1 - side]; k = (k + 1) % loop.size())
      t.ends[side].push_back(&f.edges[static_cast<size_t>(loop[k].edge)]);
  return !t.ends[0].empty() && !t.ends[1].empty();
}

}  // namespace

std::set<size_t> map_thin_tubes(const wefm_cad::CadModel& model, double h, const std::vector<double>& face_sizes,
                                std::map<long long, wefm_cad::EdgeNodes>& edge_nodes) {
  std::set<size_t> mapped;
  for (size_t i = 0; i < model.faces.size(); ++i) {
    const wefm_cad::CadFace& f = model.faces[i];
    Tube tube;
    if (!(i < face_sizes.size() && face_sizes[i] < h) || !tube_of(f, tube)) continue;
    const auto seam_nodes = edge_nodes.find(tube.seam->id);
    if (seam_nodes == edge_nodes.end()) continue;
    // Both ends with as many segments (the rows of the strip run from one to the other).
    size_t segments[2] = {0, 0};
    double length = 0;
    bool known = true;
    for (size_t side = 0; side < 2; ++side)
      for (const wefm_cad::CadEdge* e : tube.ends[side]) {
        const auto it = edge_nodes.find(e->id);
        if (it == edge_nodes.end()) known = false;
        else segments[side] += it->second.xyz.size() / 3 - 1;
        length += wefm_cad::chain_length(f, *e);
      }
    if (!known || segments[0] != segments[1] || segments[0] < kFewestRound) continue;
    const double along = std::min(h, kTubeAspect * length / static_cast<double>(2 * segments[0]));
    if (!(along > 0)) continue;
    const auto count = static_cast<long long>(std::max(1.0, std::round(wefm_cad::chain_length(f, *tube.seam) / along)));
    seam_nodes->second = wefm_cad::uniform_edge_nodes(f, *tube.seam, count);
    mapped.insert(i);
  }
  return mapped;
}

}  // namespace wefm_cli
