// split_pinched_vertices: fans by facet adjacency, chains moved onto the copies, loops re-walked.
#include "cad_face_repair.hpp"

#include <algorithm>
#include <map>
#include <numeric>
#include <utility>

namespace wefm_cad {

namespace {

using Pair = std::pair<int32_t, int32_t>;

struct DisjointSet {
  std::vector<size_t> parent;
  explicit DisjointSet(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), size_t{0}); }
  size_t find(size_t a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  }
  void unite(size_t a, size_t b) { parent[find(a)] = find(b); }
};

int32_t corner(const std::vector<int32_t>& t, size_t tri, size_t c) { return t[3 * tri + c % 3]; }

// Splits the vertices with more than one fan; copy_at[(v, w)] is the vertex that stands for v in the
// facets on the facet edge (v, w), both in the ids before the split. Returns the vertices added.
int split_fans(CadFace& f, std::map<Pair, int32_t>& copy_at, std::vector<bool>& was_split) {
  const std::vector<int32_t> before = f.triangles;
  const size_t nt = before.size() / 3, nv = f.xyz.size() / 3;
  std::map<Pair, std::vector<size_t>> edge_tris;
  std::vector<std::vector<size_t>> corners(nv);
  for (size_t k = 0; k < before.size(); ++k) {
    edge_tris[std::minmax(before[k], corner(before, k / 3, k % 3 + 1))].push_back(k / 3);
    corners[static_cast<size_t>(before[k])].push_back(k);
  }
  was_split.assign(nv, false);
  int added = 0;
  for (size_t v = 0; v < nv; ++v) {
    const std::vector<size_t>& cs = corners[v];
    if (cs.size() < 2) continue;
    std::map<size_t, size_t> local;  // triangle -> its corner's place in cs (a facet has v once)
    for (size_t i = 0; i < cs.size(); ++i) local[cs[i] / 3] = i;
    DisjointSet fans(cs.size());
    for (size_t i = 0; i < cs.size(); ++i)
      for (size_t c = 1; c < 3; ++c) {
        const std::vector<size_t>& ts = edge_tris[std::minmax(static_cast<int32_t>(v), corner(before, cs[i] / 3, cs[i] % 3 + c))];
        if (ts.size() == 2 && local.count(ts[0]) && local.count(ts[1])) fans.unite(local[ts[0]], local[ts[1]]);
      }
    std::map<size_t, int32_t> id_of_fan;
    for (size_t i = 0; i < cs.size(); ++i) {
      auto [it, fresh] = id_of_fan.emplace(fans.find(i), static_cast<int32_t>(v));
      if (fresh && id_of_fan.size() > 1) {
        it->second = static_cast<int32_t>(f.xyz.size() / 3);
        f.xyz.insert(f.xyz.end(), {f.xyz[3 * v], f.xyz[3 * v + 1], f.xyz[3 * v + 2]});
        ++added;
        was_split[v] = true;
      }
      f.triangles[cs[i]] = it->second;
    }
  }
  for (size_t t = 0; t < nt; ++t)
    for (size_t c = 0; c < 3; ++c)
      for (size_t d = 1; d < 3; ++d) copy_at[{corner(before, t, c), corner(before, t, c + d)}] = f.triangles[3 * t + c];
  return added;
}

// Each chain vertex that was split goes to the copy whose facets hold the chain's facet edge there.
void move_chains(CadFace& f, const std::map<Pair, int32_t>& copy_at, const std::vector<bool>& was_split) {
  for (CadEdge& e : f.edges) {
    const std::vector<int32_t> old = e.vertices;
    for (size_t i = 0; i < old.size(); ++i) {
      if (!was_split[static_cast<size_t>(old[i])]) continue;
      for (size_t j : {i + 1, i - 1}) {
        if (j >= old.size()) continue;
        auto it = copy_at.find({old[i], old[j]});
        if (it == copy_at.end()) continue;
        e.vertices[i] = it->second;
        break;
      }
    }
  }
}

struct Segment {
  int32_t edge = 0;
  int32_t pos = 0;  // segment index along the chain
  bool forward = true;
};

// The boundary cycles of the facets, cut along every edge chain, as loops of edge uses.
class BoundaryWalk {
 public:
  explicit BoundaryWalk(CadFace& f) : f_(f) {}

  bool run() {
    if (!index()) return false;
    std::vector<std::vector<CadEdgeUse>> loops;
    std::map<Pair, bool> walked;
    for (const auto& [h, t] : tri_of_) {
      (void)t;
      if (!segment_.count(h) || walked[h]) continue;
      std::vector<Pair> cycle;
      for (Pair cur = h; !walked[cur];) {
        walked[cur] = true;
        cycle.push_back(cur);
        if (!next(cur, cur)) return false;
        if (cycle.size() > f_.triangles.size()) return fail("a boundary cycle of the split facets does not close");
      }
      loops.emplace_back();
      if (!to_uses(cycle, loops.back())) return false;
    }
    return adopt(std::move(loops));
  }

 private:
  bool fail(const std::string& why) {
    f_.error = "pinched face repair: " + why;
    return false;
  }

  bool index() {
    for (size_t k = 0; k < f_.edges.size(); ++k) {
      const std::vector<int32_t>& c = f_.edges[k].vertices;
      if (f_.edges[k].degenerated) {
        if (!c.empty()) degenerate_at_[c.front()] = static_cast<int32_t>(k);
        continue;
      }
      for (size_t i = 0; i + 1 < c.size(); ++i) {
        if (segment_.count({c[i], c[i + 1]})) return fail("two edge chains share a facet edge");
        segment_[{c[i], c[i + 1]}] = {static_cast<int32_t>(k), static_cast<int32_t>(i), true};
        segment_[{c[i + 1], c[i]}] = {static_cast<int32_t>(k), static_cast<int32_t>(i), false};
      }
    }
    const std::vector<int32_t>& t = f_.triangles;
    for (size_t k = 0; k < t.size(); ++k)
      if (!tri_of_.emplace(Pair{t[k], corner(t, k / 3, k % 3 + 1)}, k / 3).second)
        return fail("a facet edge is used twice in the same direction");
    return true;
  }

  int32_t third(size_t tri, int32_t a, int32_t b) const {
    for (size_t c = 0; c < 3; ++c)
      if (corner(f_.triangles, tri, c) != a && corner(f_.triangles, tri, c) != b) return corner(f_.triangles, tri, c);
    return a;
  }

  // The next boundary half-edge after h: turn around h's end through the facets until a chain.
  bool next(Pair h, Pair& out) {
    const int32_t b = h.second;
    size_t tri = tri_of_.at(h);
    int32_t x = third(tri, h.first, b);
    for (size_t guard = 0; guard <= f_.triangles.size(); ++guard) {
      if (segment_.count({b, x})) {
        out = {b, x};
        return true;
      }
      auto it = tri_of_.find({x, b});
      if (it == tri_of_.end()) return fail("an open facet edge lies on no edge of the face");
      tri = it->second;
      x = third(tri, x, b);
    }
    return fail("the facets around a vertex do not end at an edge");
  }

  bool use_starts(const Segment& s) const {
    const int32_t last = static_cast<int32_t>(f_.edges[static_cast<size_t>(s.edge)].vertices.size()) - 2;
    return s.forward ? s.pos == 0 : s.pos == last;
  }

  bool to_uses(std::vector<Pair> cycle, std::vector<CadEdgeUse>& uses) {
    auto first = std::find_if(cycle.begin(), cycle.end(), [&](const Pair& h) { return use_starts(segment_.at(h)); });
    if (first == cycle.end()) return fail("a boundary cycle starts no edge");
    std::rotate(cycle.begin(), first, cycle.end());
    Segment prev;
    for (size_t i = 0; i < cycle.size(); ++i) {
      const Segment s = segment_.at(cycle[i]);
      if (use_starts(s)) {
        if (i > 0 && !(prev.forward ? prev.pos == static_cast<int32_t>(f_.edges[static_cast<size_t>(prev.edge)].vertices.size()) - 2 : prev.pos == 0))
          return fail("a boundary cycle leaves edge id " + std::to_string(f_.edges[static_cast<size_t>(prev.edge)].id) + " part way");
        uses.push_back({s.edge, !s.forward});
      } else if (s.edge != prev.edge || s.forward != prev.forward || s.pos != prev.pos + (s.forward ? 1 : -1)) {
        return fail("a boundary cycle enters edge id " + std::to_string(f_.edges[static_cast<size_t>(s.edge)].id) + " part way");
      }
      prev = s;
      auto pole = degenerate_at_.find(cycle[i].second);
      if (pole != degenerate_at_.end() && !pole_used_[pole->second]) {
        pole_used_[pole->second] = true;
        uses.push_back({pole->second, false});
      }
    }
    return true;
  }

  // The new loops replace the wires' when they use every edge as often and in the same directions.
  bool adopt(std::vector<std::vector<CadEdgeUse>> loops) {
    std::map<Pair, int> balance;
    for (const auto& loop : f_.loops)
      for (const CadEdgeUse& u : loop) ++balance[{u.edge, u.reversed}];
    for (const auto& loop : loops)
      for (const CadEdgeUse& u : loop) --balance[{u.edge, u.reversed}];
    for (const auto& [use, n] : balance)
      if (n != 0)
        return fail("the boundary cycles of the split facets use edge id " +
                    std::to_string(f_.edges[static_cast<size_t>(use.first)].id) + " differently from the wires");
    int outer = -1;
    if (f_.outer_loop >= 0 && !f_.loops[static_cast<size_t>(f_.outer_loop)].empty()) {
      const CadEdgeUse key = f_.loops[static_cast<size_t>(f_.outer_loop)].front();
      for (size_t l = 0; l < loops.size() && outer < 0; ++l)
        for (const CadEdgeUse& u : loops[l])
          if (u.edge == key.edge && u.reversed == key.reversed) outer = static_cast<int>(l);
    }
    f_.loops = std::move(loops);
    f_.outer_loop = outer;
    return true;
  }

  CadFace& f_;
  std::map<Pair, Segment> segment_;  // directed facet edge on a chain
  std::map<Pair, size_t> tri_of_;    // directed facet edge -> its facet (the face on its left)
  std::map<int32_t, int32_t> degenerate_at_;  // vertex -> degenerate edge
  std::map<int32_t, bool> pole_used_;
};

}  // namespace

int split_pinched_vertices(CadFace& face) {
  std::map<Pair, int32_t> copy_at;
  std::vector<bool> was_split;
  const int added = split_fans(face, copy_at, was_split);
  if (added == 0) return 0;
  move_chains(face, copy_at, was_split);
  return BoundaryWalk(face).run() ? added : -1;
}

}  // namespace wefm_cad
