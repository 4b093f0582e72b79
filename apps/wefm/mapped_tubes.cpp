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

// Ends whose lengths differ by at most this fraction are a tube's alike ends (a cylinder's, or one
// cut a little aslant), made to have as many segments.
constexpr double kAlikeEnds = 0.2;
// A tube with fewer segments than this round one end may lie on itself when meshed free.
constexpr size_t kFoldingRound = 5;

// Re-discretises an end of a tube (a circle, or a chain of arcs) at `count` segments in all, each
// edge evenly at a share of them by its length (at least one). False, changing nothing, where the
// edges outnumber the segments.
bool spread_round(const wefm_cad::CadFace& f, const std::vector<const wefm_cad::CadEdge*>& end, size_t count,
                  std::map<long long, wefm_cad::EdgeNodes>& edge_nodes) {
  if (end.empty() || count < end.size()) return false;
  std::vector<double> length;
  double total = 0;
  for (const wefm_cad::CadEdge* e : end) total += length.emplace_back(wefm_cad::chain_length(f, *e));
  if (!(total > 0)) return false;
  std::vector<long long> share(end.size(), 1);
  size_t given = end.size();
  // The rest one by one to the edge whose segments are longest.
  for (; given < count; ++given) {
    size_t best = 0;
    for (size_t k = 1; k < end.size(); ++k)
      if (length[k] / static_cast<double>(share[k]) > length[best] / static_cast<double>(share[best])) best = k;
    ++share[best];
  }
  for (size_t k = 0; k < end.size(); ++k) edge_nodes[end[k]->id] = wefm_cad::uniform_edge_nodes(f, *end[k], share[k]);
  return true;
}

}  // namespace

std::set<size_t> map_thin_tubes(const wefm_cad::CadModel& model, double h, const std::vector<double>& face_sizes,
                                std::map<long long, wefm_cad::EdgeNodes>& edge_nodes) {
  std::set<size_t> mapped;
  std::set<long long> mapped_ends;  // model edge ids
  for (size_t i = 0; i < model.faces.size(); ++i) {
    const wefm_cad::CadFace& f = model.faces[i];
    Tube tube;
    if (!(i < face_sizes.size() && face_sizes[i] < h) || !tube_of(f, tube)) continue;
    const auto seam_nodes = edge_nodes.find(tube.seam->id);
    if (seam_nodes == edge_nodes.end()) continue;
    // Both ends with as many segments (the rows of the strip run from one to the other).
    size_t segments[2] = {0, 0};
    double end_length[2] = {0, 0};
    bool known = true;
    for (size_t side = 0; side < 2; ++side)
      for (const wefm_cad::CadEdge* e : tube.ends[side]) {
        const auto it = edge_nodes.find(e->id);
        if (it == edge_nodes.end()) known = false;
        else segments[side] += static_cast<size_t>(it->second.segments());
        end_length[side] += wefm_cad::chain_length(f, *e);
      }
    if (!known) continue;
    // Two ends of about the same length with a few segments each, but not as many (their
    // neighbours graded them differently): the end with fewer gets as many as the other. Free, a
    // tube of three or four segments round lies on itself; one of more does not, and its ends'
    // grading is its neighbours' (made even, their triangles at the end turned to slivers). Not a
    // cone's ends either, whose small end would get segments far below its neighbours'; never an end
    // of a tube already mapped, whose ends would then differ.
    const size_t fewer = segments[0] < segments[1] ? 0 : 1;
    if (segments[0] != segments[1] && segments[fewer] < kFoldingRound &&
        std::fabs(end_length[0] - end_length[1]) <= kAlikeEnds * std::max(end_length[0], end_length[1])) {
      const bool free_to_change = std::none_of(tube.ends[fewer].begin(), tube.ends[fewer].end(),
                                               [&](const wefm_cad::CadEdge* e) { return mapped_ends.count(e->id) > 0; });
      if (free_to_change && segments[1 - fewer] <= 2 * segments[fewer] && spread_round(f, tube.ends[fewer], segments[1 - fewer], edge_nodes))
        segments[fewer] = segments[1 - fewer];
    }
    if (segments[0] != segments[1] || segments[0] < kFewestRound) continue;
    const double length = end_length[0] + end_length[1];
    const double along = std::min(h, kTubeAspect * length / static_cast<double>(2 * segments[0]));
    if (!(along > 0)) continue;
    const auto count = static_cast<long long>(std::max(1.0, std::round(wefm_cad::chain_length(f, *tube.seam) / along)));
    seam_nodes->second = wefm_cad::uniform_edge_nodes(f, *tube.seam, count);
    mapped.insert(i);
    for (const auto& end : tube.ends)
      for (const wefm_cad::CadEdge* e : end) mapped_ends.insert(e->id);
  }
  return mapped;
}

}  // namespace wefm_cli
