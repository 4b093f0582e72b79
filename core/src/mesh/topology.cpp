#include "wefm/core/mesh/topology.hpp"
#include "wefm/core/sys/huge_pages.hpp"

#include <algorithm>
#include <string>
#include <unordered_map>

#include "wefm/core/sys/error.hpp"
#include "wefm/core/mesh/union_find.hpp"

namespace wefm {
namespace {

using std::to_string;

std::uint64_t ukey(Index a, Index b) {
  std::uint64_t x = static_cast<std::uint32_t>(std::min(a, b)), y = static_cast<std::uint32_t>(std::max(a, b));
  return (x << 32) | y;
}

Index tri_vertex(const TriMesh& m, Index corner) { return m.triangles[static_cast<size_t>(corner / 3)][corner % 3]; }

// Interior facet edges to cut, as half-edges marked on both sides.
std::vector<char> mark_cuts(const TriMesh& m, const HalfEdges& he, HalfEdgeLookup& look,
                            const std::vector<std::pair<Index, Index>>& pairs, const std::string& what) {
  std::vector<char> cut(he.twin.size(), 0);
  const Index nv = static_cast<Index>(m.vertices.size());
  for (size_t i = 0; i < pairs.size(); ++i) {
    auto [a, b] = pairs[i];
    if (a < 0 || b < 0 || a >= nv || b >= nv)
      fail(Errc::invalid_topology, what + " " + to_string(i) + ": vertex index out of range (" + to_string(a) + ", " + to_string(b) + ")");
    Index h = look.find(a, b);
    if (h < 0) h = look.find(b, a);
    if (h < 0) fail(Errc::invalid_topology, what + " " + to_string(i) + ": vertices " + to_string(a) + " and " + to_string(b) + " are not joined by a facet edge");
    if (he.twin[static_cast<size_t>(h)] < 0)
      fail(Errc::invalid_topology, what + " " + to_string(i) + ": facet edge (" + to_string(a) + ", " + to_string(b) + ") lies on the mesh boundary; only interior edges can be cut");
    cut[static_cast<size_t>(h)] = cut[static_cast<size_t>(he.twin[static_cast<size_t>(h)])] = 1;
  }
  return cut;
}

}  // namespace

double loop_length_3d(const TriMesh& m, const Topology& topo, Index loop) {
  const auto& uses = topo.loop_uses[static_cast<size_t>(loop)];
  double len = 0;
  for (size_t j = 0; j < uses.size(); ++j) {
    const Vec3& p = m.vertices[static_cast<size_t>(topo.use_vertex[static_cast<size_t>(uses[j])])];
    const Vec3& q = m.vertices[static_cast<size_t>(topo.use_vertex[static_cast<size_t>(uses[(j + 1) % uses.size()])])];
    len += (q - p).norm();
  }
  return len;
}

namespace {

// The facet edges of the caller's repeated edges (used once each way by the loops), after checking
// that every edge follows facet edges and every loop uses existing edges at most twice, in
// opposite directions. fwd and bwd count each edge's uses along and against its chain.
std::vector<std::pair<Index, Index>> repeated_edge_facets(const TriMesh& m, const TopologySpec& spec, HalfEdgeLookup& look,
                                                          std::vector<int>& fwd, std::vector<int>& bwd) {
  std::vector<std::pair<Index, Index>> cut_pairs;
  const Index ne = static_cast<Index>(spec.edges.size());
  for (Index e = 0; e < ne; ++e) {
    const auto& ch = spec.edges[static_cast<size_t>(e)];
    if (ch.empty()) fail(Errc::invalid_topology, "edge " + to_string(e) + " has no vertices");
    for (size_t j = 0; j < ch.size(); ++j) {
      if (ch[j] < 0 || ch[j] >= static_cast<Index>(m.vertices.size()))
        fail(Errc::invalid_topology, "edge " + to_string(e) + ": vertex index " + to_string(ch[j]) + " at position " + to_string(j) + " is out of range");
      if (j && look.find(ch[j - 1], ch[j]) < 0 && look.find(ch[j], ch[j - 1]) < 0)
        fail(Errc::invalid_topology, "edge " + to_string(e) + " does not follow facet edges: vertices " + to_string(ch[j - 1]) + " and " + to_string(ch[j]) + " (positions " + to_string(j - 1) + ", " + to_string(j) + ") are not joined by a triangle edge");
    }
  }
  fwd.assign(static_cast<size_t>(ne), 0);
  bwd.assign(static_cast<size_t>(ne), 0);
  for (size_t l = 0; l < spec.loops.size(); ++l) {
    if (spec.loops[l].empty()) fail(Errc::invalid_topology, "loop " + to_string(l) + " has no edges");
    for (const EdgeUse& u : spec.loops[l]) {
      if (u.edge < 0 || u.edge >= ne) fail(Errc::invalid_topology, "loop " + to_string(l) + " uses edge " + to_string(u.edge) + ", which does not exist (" + to_string(ne) + " edges)");
      (u.reversed ? bwd : fwd)[static_cast<size_t>(u.edge)]++;
    }
  }
  for (Index e = 0; e < ne; ++e) {
    const int f = fwd[static_cast<size_t>(e)], b = bwd[static_cast<size_t>(e)];
    if (f + b > 2) fail(Errc::invalid_topology, "edge " + to_string(e) + " is used " + to_string(f + b) + " times by the loops (at most twice)");
    if (f == 2 || b == 2) fail(Errc::invalid_topology, "repeated edge " + to_string(e) + ": its two uses run the same direction (one must be reversed)");
    const auto& ch = spec.edges[static_cast<size_t>(e)];
    if (f == 1 && b == 1)
      for (size_t j = 1; j < ch.size(); ++j) cut_pairs.emplace_back(ch[j - 1], ch[j]);
  }
  return cut_pairs;
}

// Vertex uses: corners joined across uncut interior edges. A group's root is its smallest corner
// (UnionFind), met first in this ascending walk: uses are numbered by their first corner, and every
// later corner finds its root's use already set.
void assign_uses(const TriMesh& m, const std::vector<char>& cut, Topology& tp) {
  const HalfEdges& he = tp.he;
  const Index nh = static_cast<Index>(he.twin.size());
  UnionFind uf(nh);
  for (Index h = 0; h < nh; ++h) {
    const Index g = he.twin[static_cast<size_t>(h)];
    if (g < h || cut[static_cast<size_t>(h)]) continue;
    uf.unite(h, HalfEdges::next(g));
    uf.unite(HalfEdges::next(h), g);
  }
  assign_huge(tp.corner_use, static_cast<size_t>(nh), -1);
  for (Index c = 0; c < nh; ++c) {
    const Index r = uf.find(c);
    if (r == c) {
      tp.corner_use[static_cast<size_t>(c)] = tp.use_count++;
      tp.use_vertex.push_back(tri_vertex(m, c));
    } else {
      tp.corner_use[static_cast<size_t>(c)] = tp.corner_use[static_cast<size_t>(r)];
    }
  }
}

// The boundary cycles of the cut mesh: its boundary half-edges (mesh boundary or cut), each use's
// one outgoing boundary half-edge, and the cycles they form.
struct BoundaryCycles {
  const TriMesh& m;
  const Topology& tp;
  const std::vector<char>& cut;
  std::vector<Index> out;       // per use: its outgoing boundary half-edge (-1: interior)
  std::vector<Index> cycle_of;  // per half-edge: its cycle (-1: not on the boundary)
  std::vector<std::vector<Index>> cycles;

  BoundaryCycles(const TriMesh& mesh, const Topology& topo, const std::vector<char>& cuts) : m(mesh), tp(topo), cut(cuts) {
    const Index nh = static_cast<Index>(tp.he.twin.size());
    out.assign(static_cast<size_t>(tp.use_count), -1);
    for (Index h = 0; h < nh; ++h) {
      if (!is_bnd(h)) continue;
      Index& o = out[static_cast<size_t>(tp.corner_use[static_cast<size_t>(h)])];
      if (o >= 0) fail(Errc::invalid_topology, "vertex " + to_string(tri_vertex(m, h)) + " is pinched: its boundary is entered twice (non-manifold after cutting)");
      o = h;
    }
    cycle_of.assign(static_cast<size_t>(nh), -1);
    for (Index h = 0; h < nh; ++h) {
      if (!is_bnd(h) || cycle_of[static_cast<size_t>(h)] >= 0) continue;
      std::vector<Index> cyc;
      Index x = h;
      while (cycle_of[static_cast<size_t>(x)] < 0) {
        cycle_of[static_cast<size_t>(x)] = static_cast<Index>(cycles.size());
        cyc.push_back(x);
        x = next(x);
        if (x < 0) fail(Errc::internal, "boundary walk lost at vertex " + to_string(tri_vertex(m, cyc.back())));
      }
      cycles.push_back(std::move(cyc));
    }
  }
  bool is_bnd(Index h) const { return tp.he.twin[static_cast<size_t>(h)] < 0 || cut[static_cast<size_t>(h)]; }
  // The boundary half-edge after h.
  Index next(Index h) const { return out[static_cast<size_t>(tp.corner_use[static_cast<size_t>(HalfEdges::next(h))])]; }
};

// Each caller loop matched to one boundary cycle, checked to follow it all the way round; the
// loops' uses into tp.loop_uses.
void match_loops(const TriMesh& m, const TopologySpec& spec, HalfEdgeLookup& look, const std::vector<int>& fwd,
                 const std::vector<int>& bwd, const BoundaryCycles& bc, Topology& tp) {
  const HalfEdges& he = tp.he;
  std::vector<Index> cycle_loop(bc.cycles.size(), -1);
  for (size_t l = 0; l < spec.loops.size(); ++l) {
    std::vector<Index> hs;
    Index prev_end = -1;
    for (size_t k = 0; k < spec.loops[l].size(); ++k) {
      const EdgeUse& u = spec.loops[l][k];
      std::vector<Index> ch = spec.edges[static_cast<size_t>(u.edge)];
      if (u.reversed) std::reverse(ch.begin(), ch.end());
      if (prev_end >= 0 && ch.front() != prev_end)
        fail(Errc::invalid_topology, "loop " + to_string(l) + " does not close: edge " + to_string(u.edge) + " (use " + to_string(k) + ") starts at vertex " + to_string(ch.front()) + " but the previous edge ends at vertex " + to_string(prev_end));
      prev_end = ch.back();
      const bool repeated = fwd[static_cast<size_t>(u.edge)] == 1 && bwd[static_cast<size_t>(u.edge)] == 1;
      for (size_t j = 1; j < ch.size(); ++j) {
        const Index h = look.find(ch[j - 1], ch[j]);
        if (h < 0)
          fail(Errc::invalid_topology, "loop " + to_string(l) + " runs the wrong way along edge " + to_string(u.edge) + " at facet edge (" + to_string(ch[j - 1]) + ", " + to_string(ch[j]) + "): the face must lie on the left of every loop");
        if (!repeated && he.twin[static_cast<size_t>(h)] >= 0)
          fail(Errc::invalid_topology, "loop " + to_string(l) + " does not bound the face: edge " + to_string(u.edge) + " crosses the interior at facet edge (" + to_string(ch[j - 1]) + ", " + to_string(ch[j]) + ") and is used only once");
        hs.push_back(h);
      }
    }
    const EdgeUse& first = spec.loops[l].front();
    const auto& fch = spec.edges[static_cast<size_t>(first.edge)];
    const Index start = first.reversed ? fch.back() : fch.front();
    if (prev_end != start)
      fail(Errc::invalid_topology, "loop " + to_string(l) + " does not close: it ends at vertex " + to_string(prev_end) + " but starts at vertex " + to_string(start));
    if (hs.empty()) fail(Errc::invalid_topology, "loop " + to_string(l) + " has only degenerate (single-vertex) edges");
    for (size_t j = 0; j < hs.size(); ++j)
      if (bc.next(hs[j]) != hs[(j + 1) % hs.size()])
        fail(Errc::invalid_topology, "loop " + to_string(l) + " does not follow the face boundary at vertex " + to_string(tri_vertex(m, HalfEdges::next(hs[j]))) + ": loops cross, touch, or skip part of the boundary");
    const Index c = bc.cycle_of[static_cast<size_t>(hs[0])];
    if (cycle_loop[static_cast<size_t>(c)] >= 0)
      fail(Errc::invalid_topology, "loops " + to_string(cycle_loop[static_cast<size_t>(c)]) + " and " + to_string(l) + " describe the same boundary");
    if (hs.size() != bc.cycles[static_cast<size_t>(c)].size())
      fail(Errc::invalid_topology, "loop " + to_string(l) + " covers only part of its boundary cycle");
    cycle_loop[static_cast<size_t>(c)] = static_cast<Index>(l);
    std::vector<Index> u(hs.size());
    for (size_t j = 0; j < hs.size(); ++j) u[j] = tp.corner_use[static_cast<size_t>(hs[j])];
    tp.loop_uses.push_back(std::move(u));
  }
  for (size_t c = 0; c < bc.cycles.size(); ++c)
    if (cycle_loop[c] < 0) {
      const Index h = bc.cycles[c][0];
      fail(Errc::invalid_topology, "the loops do not bound the face: the boundary through facet edge (" + to_string(tri_vertex(m, h)) + ", " + to_string(tri_vertex(m, HalfEdges::next(h))) + ") belongs to no loop");
    }
}

// Edges and loops derived from seams alone: the seam chains (repeated edges), the boundary pieces
// between seam ends, and each cut-mesh cycle as a loop of edge uses.
class DerivedEdges {
 public:
  DerivedEdges(const TriMesh& m, const TopologySpec& spec, Topology& tp) : m_(m), tp_(tp) {
    for (auto [a, b] : spec.seams) {
      cut_adj_[a].push_back(b);
      cut_adj_[b].push_back(a);
    }
    for (auto& [v, nb] : cut_adj_) {
      std::sort(nb.begin(), nb.end());
      nb.erase(std::unique(nb.begin(), nb.end()), nb.end());
    }
    on_mesh_bnd_.assign(m.vertices.size(), 0);
    const Index nh = static_cast<Index>(tp.he.twin.size());
    for (Index h = 0; h < nh; ++h)
      if (tp.he.twin[static_cast<size_t>(h)] < 0) on_mesh_bnd_[static_cast<size_t>(tri_vertex(m, h))] = 1;
  }

  void seam_chains();
  void boundary_pieces();
  void loops(const BoundaryCycles& bc);

 private:
  // A seam vertex where chains end: not on exactly two seam facet edges, or on the mesh boundary.
  bool is_node(Index v) const {
    auto it = cut_adj_.find(v);
    return it != cut_adj_.end() && (it->second.size() != 2 || on_mesh_bnd_[static_cast<size_t>(v)]);
  }
  Index add_chain(std::vector<Index> ch) {
    const Index e = static_cast<Index>(tp_.edges.size());
    for (size_t j = 1; j < ch.size(); ++j) where_[ukey(ch[j - 1], ch[j])] = {e, static_cast<Index>(j - 1), ch[j - 1] < ch[j]};
    tp_.edges.push_back(std::move(ch));
    return e;
  }
  // The seam chain that starts with facet edge (v0, v1), up to a node or back at v0.
  std::vector<Index> walk_from(Index v0, Index v1) {
    std::vector<Index> ch{v0, v1};
    walked_[ukey(v0, v1)] = 1;
    while (!is_node(ch.back()) && ch.back() != v0) {
      const auto& nb = cut_adj_[ch.back()];
      const Index nxt = nb[0] == ch[ch.size() - 2] ? nb[1] : nb[0];
      if (walked_.count(ukey(ch.back(), nxt))) break;
      walked_[ukey(ch.back(), nxt)] = 1;
      ch.push_back(nxt);
    }
    return ch;
  }

  const TriMesh& m_;
  Topology& tp_;
  std::unordered_map<Index, std::vector<Index>> cut_adj_;
  std::vector<char> on_mesh_bnd_;
  // facet edge -> (edge id, index of its first chain vertex, chain runs a->b)
  struct Where {
    Index edge, pos;
    bool forward;
  };
  std::unordered_map<std::uint64_t, Where> where_;
  std::unordered_map<std::uint64_t, char> walked_;
};

void DerivedEdges::seam_chains() {
  std::vector<Index> seam_vertices;
  for (auto& kv : cut_adj_) seam_vertices.push_back(kv.first);
  std::sort(seam_vertices.begin(), seam_vertices.end());
  for (Index v : seam_vertices)
    if (is_node(v))
      for (Index w : cut_adj_[v])
        if (!walked_.count(ukey(v, w))) add_chain(walk_from(v, w));
  for (Index v : seam_vertices)  // closed seams without any node
    for (Index w : cut_adj_[v])
      if (!walked_.count(ukey(v, w))) add_chain(walk_from(v, w));
}

// The mesh's boundary cycles split at seam nodes.
void DerivedEdges::boundary_pieces() {
  const HalfEdges& he = tp_.he;
  const Index nh = static_cast<Index>(he.twin.size());
  std::vector<char> seen(static_cast<size_t>(nh), 0);
  for (Index h0 = 0; h0 < nh; ++h0) {
    if (he.twin[static_cast<size_t>(h0)] >= 0 || seen[static_cast<size_t>(h0)]) continue;
    std::vector<Index> ring;  // original boundary half-edges in order
    for (Index x = h0; !seen[static_cast<size_t>(x)];) {
      seen[static_cast<size_t>(x)] = 1;
      ring.push_back(x);
      Index y = HalfEdges::next(x);
      while (he.twin[static_cast<size_t>(y)] >= 0) y = HalfEdges::next(he.twin[static_cast<size_t>(y)]);
      x = y;
    }
    size_t s0 = 0;
    bool any = false;
    for (size_t j = 0; j < ring.size(); ++j)
      if (is_node(tri_vertex(m_, ring[j]))) {
        s0 = j;
        any = true;
        break;
      }
    std::vector<Index> ch{tri_vertex(m_, ring[s0])};
    for (size_t k = 0; k < ring.size(); ++k) {
      const Index h = ring[(s0 + k) % ring.size()];
      const Index b = tri_vertex(m_, HalfEdges::next(h));
      ch.push_back(b);
      if ((any && is_node(b)) || k + 1 == ring.size()) {
        add_chain(ch);
        ch = {b};
      }
    }
  }
}

// Each cut-mesh cycle as edge uses, starting at an edge start.
void DerivedEdges::loops(const BoundaryCycles& bc) {
  for (const auto& cyc : bc.cycles) {
    auto info = [&](Index h) {
      const Index a = tri_vertex(m_, h), b = tri_vertex(m_, HalfEdges::next(h));
      const Where w = where_.at(ukey(a, b));
      const bool along = (a < b) == w.forward;  // traversal agrees with the chain direction
      return std::make_pair(w, along);
    };
    size_t s0 = 0;
    for (size_t j = 0; j < cyc.size(); ++j) {
      auto [w, along] = info(cyc[j]);
      const Index last = static_cast<Index>(tp_.edges[static_cast<size_t>(w.edge)].size()) - 2;
      if ((along && w.pos == 0) || (!along && w.pos == last)) {
        s0 = j;
        break;
      }
    }
    std::vector<EdgeUse> loop;
    for (size_t k = 0; k < cyc.size(); ++k) {
      auto [w, along] = info(cyc[(s0 + k) % cyc.size()]);
      const Index last = static_cast<Index>(tp_.edges[static_cast<size_t>(w.edge)].size()) - 2;
      if ((along && w.pos == 0) || (!along && w.pos == last)) loop.push_back({w.edge, !along});
    }
    tp_.loops.push_back(std::move(loop));
    std::vector<Index> u(cyc.size());
    for (size_t j = 0; j < cyc.size(); ++j) u[j] = tp_.corner_use[static_cast<size_t>(cyc[j])];
    tp_.loop_uses.push_back(std::move(u));
  }
}

// The edges used twice by the loops, with the uses of their two sides.
void find_repeated_edges(HalfEdgeLookup& look, Topology& tp) {
  const HalfEdges& he = tp.he;
  tp.edge_repeated.assign(tp.edges.size(), -1);
  std::vector<int> uses_of(tp.edges.size(), 0);
  for (const auto& lp : tp.loops)
    for (const EdgeUse& u : lp) uses_of[static_cast<size_t>(u.edge)]++;
  for (Index e = 0; e < static_cast<Index>(tp.edges.size()); ++e) {
    const auto& ch = tp.edges[static_cast<size_t>(e)];
    if (uses_of[static_cast<size_t>(e)] != 2 || ch.size() < 2) continue;
    RepeatedEdge r;
    r.edge = e;
    r.side_a.assign(ch.size(), -1);
    r.side_b.assign(ch.size(), -1);
    for (size_t j = 0; j + 1 < ch.size(); ++j) {
      const Index h = look.find(ch[j], ch[j + 1]);
      const Index g = h < 0 ? -1 : he.twin[static_cast<size_t>(h)];
      if (h < 0 || g < 0) fail(Errc::invalid_topology, "repeated edge " + to_string(e) + " is not interior at facet edge (" + to_string(ch[j]) + ", " + to_string(ch[j + 1]) + ")");
      if (r.side_a[j] < 0) r.side_a[j] = tp.corner_use[static_cast<size_t>(h)];
      r.side_a[j + 1] = tp.corner_use[static_cast<size_t>(HalfEdges::next(h))];
      if (r.side_b[j] < 0) r.side_b[j] = tp.corner_use[static_cast<size_t>(HalfEdges::next(g))];
      r.side_b[j + 1] = tp.corner_use[static_cast<size_t>(g)];
    }
    tp.edge_repeated[static_cast<size_t>(e)] = static_cast<Index>(tp.repeated.size());
    tp.repeated.push_back(std::move(r));
  }
}

// The caller's outer loop, or the longest in 3D.
Index outer_loop(const TriMesh& m, const TopologySpec& spec, const Topology& tp) {
  const Index nl = static_cast<Index>(tp.loops.size());
  if (spec.outer_loop >= 0) {
    if (spec.outer_loop >= nl) fail(Errc::invalid_topology, "outer loop " + to_string(spec.outer_loop) + " does not exist (" + to_string(nl) + " loops)");
    return spec.outer_loop;
  }
  Index outer = tp.outer_loop;
  double best = -1;
  for (Index l = 0; l < nl; ++l) {
    const double len = loop_length_3d(m, tp, l);
    if (len > best * (1 + 1e-12)) {
      best = len;
      outer = l;
    }
  }
  return outer;
}

}  // namespace

Topology build_topology(const TriMesh& m, const TopologySpec& spec, const HalfEdges* half_edges) {
  Topology tp;
  tp.he = half_edges ? *half_edges : build_halfedges(m.triangles, static_cast<Index>(m.vertices.size()));
  HalfEdgeLookup look(m.triangles, static_cast<Index>(m.vertices.size()));
  const bool given = !spec.loops.empty();
  tp.derived = !given;

  std::vector<int> fwd, bwd;
  const std::vector<std::pair<Index, Index>> cut_pairs = given ? repeated_edge_facets(m, spec, look, fwd, bwd) : spec.seams;
  const std::vector<char> cut = mark_cuts(m, tp.he, look, cut_pairs, given ? "repeated edge facet" : "seam");
  assign_uses(m, cut, tp);
  const BoundaryCycles bc(m, tp, cut);
  if (bc.cycles.empty())
    fail(Errc::invalid_topology, "closed surface with no boundary and no cut: give seams (facet edges to cut along) or loops with a repeated edge, or turn on the automatic cut (genus 0 only)",
         Remedy::seams_or_cut);
  if (given) {
    tp.edges = spec.edges;
    tp.loops = spec.loops;
    match_loops(m, spec, look, fwd, bwd, bc, tp);
  } else {
    DerivedEdges derived(m, spec, tp);
    derived.seam_chains();
    derived.boundary_pieces();
    derived.loops(bc);
  }
  find_repeated_edges(look, tp);
  tp.use_on_loop.assign(static_cast<size_t>(tp.use_count), 0);
  for (const auto& lu : tp.loop_uses)
    for (Index u : lu) tp.use_on_loop[static_cast<size_t>(u)] = 1;
  tp.outer_loop = outer_loop(m, spec, tp);
  return tp;
}

}  // namespace wefm
