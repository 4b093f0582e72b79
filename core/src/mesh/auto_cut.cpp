#include "wefm/core/mesh/auto_cut.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <string>

#include "wefm/core/sys/error.hpp"
#include "wefm/core/mesh/halfedges.hpp"
#include "wefm/core/mesh/union_find.hpp"

namespace wefm {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// A vertex whose angle deficit exceeds this is a cone the layout cannot absorb without visible
// distortion (a box corner has 90 deg); a smooth mesh's deficits are far below it.
constexpr double kSharpDeficit = kPi / 6;
// Greedy threading costs one Dijkstra per cone: a bound keeps the whole cut O(n log n).
constexpr size_t kMaxCones = 32;

Index tri_vertex(const TriMesh& m, Index corner) { return m.triangles[static_cast<size_t>(corner / 3)][corner % 3]; }

// Undirected facet-edge graph in CSR form, weighted by 3D length; neighbours sorted by index.
struct Graph {
  std::vector<Index> start, nbr;
  std::vector<double> len;
};

Graph edge_graph(const TriMesh& m, const HalfEdges& he) {
  const size_t nv = m.vertices.size();
  Graph g;
  g.start.assign(nv + 1, 0);
  const Index nh = static_cast<Index>(he.twin.size());
  auto each_edge = [&](auto&& fn) {
    for (Index h = 0; h < nh; ++h) {
      const Index t = he.twin[static_cast<size_t>(h)];
      if (t < 0 || h < t) fn(tri_vertex(m, h), tri_vertex(m, HalfEdges::next(h)));
    }
  };
  each_edge([&](Index a, Index b) {
    ++g.start[static_cast<size_t>(a) + 1];
    ++g.start[static_cast<size_t>(b) + 1];
  });
  for (size_t i = 1; i <= nv; ++i) g.start[i] += g.start[i - 1];
  std::vector<std::pair<Index, double>> adj(static_cast<size_t>(g.start[nv]));
  std::vector<Index> fill(g.start.begin(), g.start.end() - 1);
  each_edge([&](Index a, Index b) {
    const double l = (m.vertices[static_cast<size_t>(a)] - m.vertices[static_cast<size_t>(b)]).norm();
    adj[static_cast<size_t>(fill[static_cast<size_t>(a)]++)] = {b, l};
    adj[static_cast<size_t>(fill[static_cast<size_t>(b)]++)] = {a, l};
  });
  for (size_t v = 0; v < nv; ++v) std::sort(adj.begin() + g.start[v], adj.begin() + g.start[v + 1]);
  for (const auto& [b, l] : adj) {
    g.nbr.push_back(b);
    g.len.push_back(l);
  }
  return g;
}

// Multi-source Dijkstra. Blocked vertices are never entered; the search ends when a target is
// settled and returns it. Without a target settled, returns the farthest vertex reached (lowest
// index among equals), or -1. The queue orders equal distances by vertex index: deterministic.
struct Search {
  std::vector<double> dist;
  std::vector<Index> pred;
};

Index dijkstra(const Graph& g, const std::vector<Index>& sources, const std::vector<char>* blocked,
               const std::vector<char>* target, Search& s) {
  const size_t nv = g.start.size() - 1;
  s.dist.assign(nv, kInf);
  s.pred.assign(nv, -1);
  using Item = std::pair<double, Index>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> q;
  for (Index v : sources) {
    s.dist[static_cast<size_t>(v)] = 0;
    q.push({0.0, v});
  }
  std::vector<char> done(nv, 0);
  Index far = -1;
  while (!q.empty()) {
    const auto [d, v] = q.top();
    q.pop();
    if (done[static_cast<size_t>(v)]) continue;
    done[static_cast<size_t>(v)] = 1;
    if (target && (*target)[static_cast<size_t>(v)]) return v;
    if (far < 0 || d > s.dist[static_cast<size_t>(far)] || (d == s.dist[static_cast<size_t>(far)] && v < far)) far = v;
    for (Index k = g.start[static_cast<size_t>(v)]; k < g.start[static_cast<size_t>(v) + 1]; ++k) {
      const Index w = g.nbr[static_cast<size_t>(k)];
      if (blocked && (*blocked)[static_cast<size_t>(w)]) continue;
      const double nd = d + g.len[static_cast<size_t>(k)];
      if (nd < s.dist[static_cast<size_t>(w)]) {
        s.dist[static_cast<size_t>(w)] = nd;
        s.pred[static_cast<size_t>(w)] = v;
        q.push({nd, w});
      }
    }
  }
  return target ? -1 : far;
}

// Vertices from the search's source to v.
std::vector<Index> path_to(const Search& s, Index v) {
  std::vector<Index> p;
  for (; v >= 0; v = s.pred[static_cast<size_t>(v)]) p.push_back(v);
  std::reverse(p.begin(), p.end());
  return p;
}

void append_path(const TriMesh& m, const std::vector<Index>& path, AutoCut& cut) {
  for (size_t j = 1; j < path.size(); ++j) {
    cut.seams.emplace_back(path[j - 1], path[j]);
    cut.length += (m.vertices[static_cast<size_t>(path[j])] - m.vertices[static_cast<size_t>(path[j - 1])]).norm();
  }
}

Index first_referenced(const TriMesh& m) {
  Index v0 = std::numeric_limits<Index>::max();
  for (const Tri& t : m.triangles)
    for (Index v : t) v0 = std::min(v0, v);
  return v0;
}

std::vector<Index> farthest_pair_path(const Graph& g, Index v0) {
  Search s;
  const Index a = dijkstra(g, {v0}, nullptr, nullptr, s);
  const Index b = dijkstra(g, {a}, nullptr, nullptr, s);
  return path_to(s, b);
}

// Angle deficit 2 pi - sum of corner angles, per vertex (the discrete Gaussian curvature).
std::vector<double> angle_deficits(const TriMesh& m) {
  std::vector<double> d(m.vertices.size(), 2 * kPi);
  for (const Tri& t : m.triangles)
    for (int j = 0; j < 3; ++j) {
      const Vec3& p = m.vertices[static_cast<size_t>(t[j])];
      const Vec3 e1 = m.vertices[static_cast<size_t>(t[(j + 1) % 3])] - p, e2 = m.vertices[static_cast<size_t>(t[(j + 2) % 3])] - p;
      d[static_cast<size_t>(t[j])] -= std::atan2(e1.cross(e2).norm(), e1.dot(e2));
    }
  return d;
}

// A path that threads the cone vertices greedily (nearest unvisited cone next, never re-entering the
// path), so cutting it removes their curvature from the layout; empty if there are fewer than two.
std::vector<Index> cone_path(const TriMesh& m, const Graph& g) {
  const std::vector<double> def = angle_deficits(m);
  std::vector<Index> cones;
  std::vector<char> used(m.vertices.size(), 0);
  for (const Tri& t : m.triangles)
    for (Index v : t) used[static_cast<size_t>(v)] = 1;
  for (Index v = 0; v < static_cast<Index>(m.vertices.size()); ++v)
    if (used[static_cast<size_t>(v)] && std::abs(def[static_cast<size_t>(v)]) > kSharpDeficit) cones.push_back(v);
  if (cones.size() < 2) return {};
  std::stable_sort(cones.begin(), cones.end(), [&](Index a, Index b) { return std::abs(def[static_cast<size_t>(a)]) > std::abs(def[static_cast<size_t>(b)]); });
  if (cones.size() > kMaxCones) cones.resize(kMaxCones);
  std::sort(cones.begin(), cones.end());
  std::vector<char> todo(m.vertices.size(), 0);
  for (Index c : cones) todo[static_cast<size_t>(c)] = 1;
  // Start at the cone farthest from the lowest-numbered one: the greedy tour then runs one way.
  Search s;
  dijkstra(g, {cones.front()}, nullptr, nullptr, s);
  Index start = cones.front();
  for (Index c : cones)
    if (s.dist[static_cast<size_t>(c)] > s.dist[static_cast<size_t>(start)]) start = c;
  std::vector<Index> path{start};
  std::vector<char> on_path(m.vertices.size(), 0);
  on_path[static_cast<size_t>(start)] = 1;
  todo[static_cast<size_t>(start)] = 0;
  for (size_t left = cones.size() - 1; left > 0; --left) {
    const Index end = path.back();
    on_path[static_cast<size_t>(end)] = 0;  // the source itself is not blocked
    const Index next = dijkstra(g, {end}, &on_path, &todo, s);
    on_path[static_cast<size_t>(end)] = 1;
    if (next < 0) break;  // the remaining cones are walled off by the path: stop there
    const std::vector<Index> leg = path_to(s, next);
    for (size_t j = 1; j < leg.size(); ++j) {
      path.push_back(leg[j]);
      on_path[static_cast<size_t>(leg[j])] = 1;
    }
    todo[static_cast<size_t>(next)] = 0;
  }
  return path;
}

std::vector<Index> shortest_edge_path(const Graph& g) {
  Index a = -1, b = -1;
  double best = kInf;
  for (Index v = 0; v + 1 < static_cast<Index>(g.start.size()); ++v)
    for (Index k = g.start[static_cast<size_t>(v)]; k < g.start[static_cast<size_t>(v) + 1]; ++k)
      if (g.nbr[static_cast<size_t>(k)] > v && g.len[static_cast<size_t>(k)] < best) {
        best = g.len[static_cast<size_t>(k)];
        a = v;
        b = g.nbr[static_cast<size_t>(k)];
      }
  return {a, b};
}

}  // namespace

AutoCut compute_auto_cut(const TriMesh& m, SlitRule rule) {
  AutoCut cut;
  const Index nv = static_cast<Index>(m.vertices.size());
  const HalfEdges he = build_halfedges(m.triangles, nv);
  const Index nh = static_cast<Index>(he.twin.size());

  // Boundary cycles as components of the boundary edges.
  UnionFind uf(nv);
  std::vector<char> on_bnd(static_cast<size_t>(nv), 0);
  Index bnd_half_edges = 0;
  for (Index h = 0; h < nh; ++h)
    if (he.twin[static_cast<size_t>(h)] < 0) {
      const Index a = tri_vertex(m, h), b = tri_vertex(m, HalfEdges::next(h));
      on_bnd[static_cast<size_t>(a)] = on_bnd[static_cast<size_t>(b)] = 1;
      uf.unite(a, b);
      ++bnd_half_edges;
    }
  std::vector<Index> roots;
  for (Index v = 0; v < nv; ++v)
    if (on_bnd[static_cast<size_t>(v)] && uf.find(v) == v) roots.push_back(v);

  if (roots.size() == 2) {
    // Annulus: shortest path from any vertex of the cycle through the lowest-numbered boundary
    // vertex to any vertex of the other. Both cycles' vertices stop the search, so only the path's
    // ends touch them.
    const Graph g = edge_graph(m, he);
    std::vector<Index> sources;
    std::vector<char> other(static_cast<size_t>(nv), 0);
    for (Index v = 0; v < nv; ++v) {
      if (!on_bnd[static_cast<size_t>(v)]) continue;
      if (uf.find(v) == roots[0])
        sources.push_back(v);
      else
        other[static_cast<size_t>(v)] = 1;
    }
    Search s;
    const Index t = dijkstra(g, sources, nullptr, &other, s);
    if (t < 0) fail(Errc::invalid_topology, "automatic cut: the two boundary loops are not joined by facet edges");
    cut.kind = AutoCutKind::Annulus;
    append_path(m, path_to(s, t), cut);
    return cut;
  }
  if (!roots.empty()) return cut;  // a disk, or more than two loops: the boundary term suffices

  // Closed surface: Euler characteristic V - E + F of the referenced vertices.
  std::vector<char> used(static_cast<size_t>(nv), 0);
  for (const Tri& t : m.triangles)
    for (Index v : t) used[static_cast<size_t>(v)] = 1;
  std::int64_t V = 0;
  for (char u : used) V += u;
  const std::int64_t F = static_cast<std::int64_t>(m.triangles.size());
  const std::int64_t E = (3 * F + bnd_half_edges) / 2;
  const std::int64_t chi = V - E + F;
  if (chi != 2) {
    const std::int64_t genus = (2 - chi) / 2;
    fail(Errc::invalid_topology, "automatic cut: the face is a closed surface of genus " + std::to_string(genus) + " (Euler characteristic " +
                                     std::to_string(chi) + ", " + std::to_string(genus) + (genus == 1 ? " handle" : " handles") +
                                     "); the automatic cut cuts only genus 0. Give seams that cut every handle open",
         Remedy::add_seams);
  }
  const Graph g = edge_graph(m, he);
  std::vector<Index> path;
  if (rule == SlitRule::SharpThenFarthest) path = cone_path(m, g);
  if (rule == SlitRule::ShortestEdge) path = shortest_edge_path(g);
  if (path.size() < 2) path = farthest_pair_path(g, first_referenced(m));
  cut.kind = AutoCutKind::Closed;
  append_path(m, path, cut);
  return cut;
}

}  // namespace wefm
