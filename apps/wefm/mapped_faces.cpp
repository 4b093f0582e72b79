#include "mapped_faces.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>

#include "face_corners.hpp"

namespace wefm_cli {

bool four_sides(const wefm_cad::CadFace& f, FourSides& sides, std::string& why) {
  if (!f.error.empty()) return why = "not imported", false;
  if (f.loops.size() != 1) return why = "holes", false;
  const auto& loop = f.loops[0];
  for (const wefm_cad::CadEdgeUse& u : loop)
    if (f.edges[static_cast<size_t>(u.edge)].degenerated || f.edges[static_cast<size_t>(u.edge)].vertices.size() < 2)
      return why = "a pole", false;
  const std::vector<FaceCorner> corners = face_corners(f);
  if (corners.size() != loop.size()) return why = "edges that do not meet", false;
  // corners[k] is where use k ends.
  std::vector<size_t> at;
  for (size_t k = 0; k < corners.size(); ++k) {
    const double d = corners[k].degrees;
    if (std::fabs(d - 180) < kSmoothTurnDegrees) continue;
    if (d < kFewestCornerDegrees || d > kCornerDegrees) {
      char text[64];
      std::snprintf(text, sizeof text, "a corner of %.0f degrees", d);
      return why = text, false;
    }
    at.push_back(k);
  }
  if (at.size() != 4) return why = std::to_string(at.size()) + " corners", false;
  for (size_t s = 0; s < 4; ++s) {
    sides.corners[s] = corners[at[s]].vertex;
    sides.edges[s].clear();
    sides.length[s] = 0;
    for (size_t k = (at[s] + 1) % loop.size();; k = (k + 1) % loop.size()) {
      const wefm_cad::CadEdge& e = f.edges[static_cast<size_t>(loop[k].edge)];
      sides.edges[s].push_back(e.id);
      sides.length[s] += wefm_cad::chain_length(f, e);
      if (k == at[(s + 1) % 4]) break;
    }
  }
  for (size_t s = 0; s < 2; ++s) {
    const double a = sides.length[s], b = sides.length[s + 2];
    if (!(a > 0 && b > 0) || std::max(a, b) > kSideRatio * std::min(a, b)) return why = "opposite sides of unlike lengths", false;
  }
  return true;
}

namespace {

// Opposite sides with as many segments: the sums of their edges' counts equal.
struct Tie {
  std::vector<long long> a, b;
};

// The segment counts of the model's edges under the ties of the faces taken so far.
class CountMatcher {
 public:
  CountMatcher(const wefm_cad::CadModel& model, const std::map<long long, wefm_cad::EdgeNodes>& nodes) {
    for (const auto& [id, en] : nodes) count_[id] = target_[id] = en.segments();
    for (const wefm_cad::CadFace& f : model.faces)
      for (const wefm_cad::CadEdge& e : f.edges)
        if (nodes.count(e.id) && !length_.count(e.id)) length_[e.id] = wefm_cad::chain_length(f, e);
  }
  void fix(long long id) { fixed_.insert(id); }

  // Adds the face's two ties and adds segments until every tie holds; false with `why`, leaving
  // the counts and ties as they were, where that would take an edge past its growth or a fixed edge.
  bool take(const FourSides& s, std::string& why) {
    for (const auto& side : s.edges)
      for (long long id : side)
        if (!count_.count(id)) return why = "edge " + std::to_string(id) + " has no nodes", false;
    const size_t first = ties_.size();
    std::vector<std::pair<long long, long long>> undo;  // edge, count before
    std::deque<size_t> queue;
    for (size_t k = 0; k < 2; ++k) {
      for (long long id : s.edges[k]) tied_[id].push_back(ties_.size());
      for (long long id : s.edges[k + 2]) tied_[id].push_back(ties_.size());
      queue.push_back(ties_.size());
      ties_.push_back({s.edges[k], s.edges[k + 2]});
    }
    bool ok = true;
    for (size_t steps = 0; ok && !queue.empty(); ++steps) {
      const Tie& t = ties_[queue.front()];
      queue.pop_front();
      long long diff = sum(t.a) - sum(t.b);
      const std::vector<long long>& fewer = diff < 0 ? t.a : t.b;
      const std::vector<long long>& more = diff < 0 ? t.b : t.a;
      for (diff = std::llabs(diff); ok && diff > 0; --diff) {
        const long long id = grow_pick(fewer, more);
        if (id < 0 || steps > kMostSteps) {
          char text[160];
          std::snprintf(text, sizeof text, "opposite sides of %lld and %lld segments: the fewer cannot grow to match (%s)", sum(fewer),
                        sum(more), steps > kMostSteps ? "too many steps" : "at most doubled, the mapped tubes' not at all");
          why = text;
          ok = false;
          break;
        }
        undo.push_back({id, count_[id]});
        ++count_[id];
        for (size_t other : tied_[id]) queue.push_back(other);
      }
    }
    if (ok) return true;
    for (auto it = undo.rbegin(); it != undo.rend(); ++it) count_[it->first] = it->second;
    for (size_t k = first; k < ties_.size(); ++k)
      for (const auto* side : {&ties_[k].a, &ties_[k].b})
        for (long long id : *side) {
          auto& v = tied_[id];
          v.erase(std::remove(v.begin(), v.end(), k), v.end());
        }
    ties_.resize(first);
    return false;
  }

  const std::map<long long, long long>& counts() const { return count_; }
  long long target(long long id) const { return target_.at(id); }

 private:
  // Ties looked at before a face is given up: the counts grow by one a step, boundedly.
  static constexpr size_t kMostSteps = 100000;

  long long sum(const std::vector<long long>& side) const {
    long long n = 0;
    for (long long id : side) n += count_.at(id);
    return n;
  }
  // The edge of `fewer` (not also on `more` as often: a seam on both sides gains nothing) whose
  // segments are longest, free to grow; -1 if none.
  long long grow_pick(const std::vector<long long>& fewer, const std::vector<long long>& more) const {
    long long best = -1;
    double best_step = -1;
    for (long long id : fewer) {
      if (std::count(fewer.begin(), fewer.end(), id) <= std::count(more.begin(), more.end(), id)) continue;
      const long long n = count_.at(id), t = target_.at(id);
      if (fixed_.count(id) || static_cast<double>(n + 1) > std::max(static_cast<double>(t + 1), kMostGrowth * static_cast<double>(t)))
        continue;
      const double step = length_.count(id) ? length_.at(id) / static_cast<double>(n) : 0;
      if (step > best_step) best = id, best_step = step;
    }
    return best;
  }

  std::map<long long, long long> count_, target_;
  std::map<long long, double> length_;
  std::set<long long> fixed_;
  std::vector<Tie> ties_;
  std::map<long long, std::vector<size_t>> tied_;
};

}  // namespace

MappedFaces map_four_sided_faces(const wefm_cad::CadModel& model, const std::vector<size_t>& named, bool automatic,
                                 const std::set<size_t>& fixed, const std::set<long long>& unsettled,
                                 std::map<long long, wefm_cad::EdgeNodes>& edge_nodes) {
  MappedFaces out;
  CountMatcher matcher(model, edge_nodes);
  for (size_t i : fixed)
    for (const wefm_cad::CadEdge& e : model.faces[i].edges) matcher.fix(e.id);
  std::vector<size_t> order(named.begin(), named.end());
  const std::set<size_t> is_named(named.begin(), named.end());
  if (automatic) {
    std::vector<size_t> rest;
    for (size_t i = 0; i < model.faces.size(); ++i)
      if (!is_named.count(i) && !fixed.count(i)) rest.push_back(i);
    std::vector<double> area(model.faces.size(), 0);
    for (size_t i : rest) area[i] = wefm_cad::face_area(model.faces[i]);
    std::stable_sort(rest.begin(), rest.end(), [&](size_t a, size_t b) { return area[a] > area[b]; });
    order.insert(order.end(), rest.begin(), rest.end());
  }
  for (size_t i : order) {
    FourSides sides;
    std::string why;
    if (!four_sides(model.faces[i], sides, why)) {
      // A named face is the library's to judge (its corners are then the domain's sharpest four).
      if (is_named.count(i)) out.faces.insert(i), out.refused[i] = "not four-sided by its corners (" + why + ")";
      continue;
    }
    ++out.four_sided;
    if (!is_named.count(i) &&
        std::any_of(model.faces[i].edges.begin(), model.faces[i].edges.end(), [&](const wefm_cad::CadEdge& e) { return unsettled.count(e.id) > 0; })) {
      out.refused[i] = "an edge's nodes follow a face lying on another";
      continue;
    }
    const bool matched = matcher.take(sides, why);
    if (matched || is_named.count(i)) out.faces.insert(i), out.sides[i] = sides;
    if (!matched) out.refused[i] = "not matched with the faces mapped before: " + why;
  }
  // Edges whose count changed, re-discretised from the first face that has them (as
  // discretise_model_edges takes them).
  for (const wefm_cad::CadFace& f : model.faces)
    for (const wefm_cad::CadEdge& e : f.edges) {
      if (!f.error.empty()) break;
      const auto it = matcher.counts().find(e.id);
      if (it == matcher.counts().end() || it->second == matcher.target(e.id) || out.recounted.count(e.id)) continue;
      auto& nodes = edge_nodes.at(e.id);
      nodes = wefm_cad::recount_edge_nodes(f, e, nodes, it->second);
      out.recounted.insert(e.id);
    }
  return out;
}

size_t mismatched_faces(const MappedFaces& m, const std::map<long long, wefm_cad::EdgeNodes>& edge_nodes) {
  auto segments = [&](const std::vector<long long>& side) {
    long long n = 0;
    for (long long id : side)
      if (const auto it = edge_nodes.find(id); it != edge_nodes.end()) n += it->second.segments();
    return n;
  };
  size_t out = 0;
  for (const auto& [i, s] : m.sides)
    out += segments(s.edges[0]) != segments(s.edges[2]) || segments(s.edges[1]) != segments(s.edges[3]);
  return out;
}

}  // namespace wefm_cli
