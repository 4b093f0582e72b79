#include "wefm/core/mesh/trimesh.hpp"
#include "wefm/core/sys/huge_pages.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "wefm/core/sys/error.hpp"
#include "wefm/core/mesh/halfedges.hpp"
#include "wefm/core/mesh/union_find.hpp"
#include "wefm/core/mesh/vertex_buckets.hpp"

namespace wefm {

double triangle_area(const TriMesh& mesh, Index t) {
  const Tri& f = mesh.triangles[static_cast<size_t>(t)];
  const Vec3& a = mesh.vertices[static_cast<size_t>(f[0])];
  return 0.5 * (mesh.vertices[static_cast<size_t>(f[1])] - a).cross(mesh.vertices[static_cast<size_t>(f[2])] - a).norm();
}

namespace {

std::string tri_str(const TriMesh& m, size_t t) {
  const Tri& f = m.triangles[t];
  return "triangle " + std::to_string(t) + " (" + std::to_string(f[0]) + ", " + std::to_string(f[1]) + ", " +
         std::to_string(f[2]) + ")";
}

// Corners of each vertex grouped into fans across shared edges; more than one fan = non-manifold vertex.
std::vector<Index> fans_per_vertex(const std::vector<Tri>& triangles, size_t vertex_count, const HalfEdges& he) {
  const Index nc = static_cast<Index>(triangles.size() * 3);
  UnionFind uf(nc);
  for (Index h = 0; h < nc; ++h) {
    const Index g = he.twin[static_cast<size_t>(h)];
    if (g < h) continue;
    // h: a->b in tri(h); g: b->a. Corner of a in tri(h) is h, in tri(g) it is next(g).
    uf.unite(h, HalfEdges::next(g));
    uf.unite(HalfEdges::next(h), g);
  }
  std::vector<Index> fans(vertex_count, 0);
  for (Index c = 0; c < nc; ++c)
    if (uf.find(c) == c) ++fans[static_cast<size_t>(triangles[static_cast<size_t>(c / 3)][c % 3])];
  return fans;
}

void throw_if_duplicates(const TriMesh& m) {
  std::vector<Tri> canon;
  const auto order = triangles_by_vertex_set(m.triangles, static_cast<Index>(m.vertices.size()), canon);
  for (size_t i = 1; i < order.size(); ++i)
    if (canon[static_cast<size_t>(order[i])] == canon[static_cast<size_t>(order[i - 1])])
      fail(Errc::invalid_mesh, "duplicate triangles: " + tri_str(m, static_cast<size_t>(order[i - 1])) + " and " +
                                   tri_str(m, static_cast<size_t>(order[i])) + " use the same vertices");
}

// The smallest vertex whose triangles form more than one fan, or -1: a walk around each vertex
// across twins. What fans_per_vertex finds, without its union-find over every corner (a third of
// the validation's memory at 1M triangles); that one still counts the fans for the message.
Index first_multi_fan_vertex(const std::vector<Tri>& triangles, size_t vertex_count, const HalfEdges& he) {
  const Index nc = static_cast<Index>(triangles.size() * 3);
  std::vector<Index> degree(vertex_count, 0), start(vertex_count, -1);
  std::vector<unsigned char> boundary_out(vertex_count, 0);
  for (Index h = 0; h < nc; ++h) {
    const size_t v = static_cast<size_t>(triangles[static_cast<size_t>(h / 3)][h % 3]);
    ++degree[v];
    if (he.twin[static_cast<size_t>(h)] < 0) {
      start[v] = h;  // an open fan is walked from its end
      if (boundary_out[v] < 2) ++boundary_out[v];
    } else if (start[v] < 0) {
      start[v] = h;
    }
  }
  for (size_t v = 0; v < vertex_count; ++v) {
    if (degree[v] == 0) continue;
    if (boundary_out[v] > 1) return static_cast<Index>(v);  // two open fans
    // h leaves v; the corner after it around v is the twin of the half-edge arriving at v in h's
    // triangle. The walk ends at the fan's other end, or back at its start on a closed fan.
    Index h = start[v], seen = 0;
    while (seen <= degree[v]) {
      ++seen;
      const Index g = he.twin[static_cast<size_t>(HalfEdges::prev(h))];
      if (g < 0 || g == start[v]) break;
      h = g;
    }
    if (seen != degree[v]) return static_cast<Index>(v);
  }
  return -1;
}

}  // namespace

namespace {

// The finite vertices' bounding box (zero for no vertices); returns how many are not finite.
std::int64_t bounding_box(const TriMesh& m, Vec3& lo, Vec3& hi) {
  lo = hi = m.vertices.empty() ? Vec3::Zero() : m.vertices[0];
  std::int64_t non_finite = 0;
  for (const Vec3& p : m.vertices) {
    if (!p.allFinite()) {
      ++non_finite;
      continue;
    }
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return non_finite;
}

// The triangles with valid, distinct corners; counts the others and the vertices none uses.
std::vector<Tri> usable_triangles(const TriMesh& m, MeshStats& s) {
  const size_t nv = m.vertices.size();
  std::vector<char> used(nv, 0);
  std::vector<Tri> good;
  good.reserve(m.triangles.size());
  for (const Tri& f : m.triangles) {
    bool ok = true;
    for (Index v : f)
      if (v < 0 || static_cast<size_t>(v) >= nv) ok = false;
    if (!ok) {
      ++s.bad_indices;
      continue;
    }
    if (f[0] == f[1] || f[1] == f[2] || f[0] == f[2]) {
      ++s.repeated_vertex_triangles;
      ++s.degenerate_triangles;
      continue;
    }
    for (Index v : f) used[static_cast<size_t>(v)] = 1;
    good.push_back(f);
  }
  for (char u : used) s.isolated_vertices += u ? 0 : 1;
  return good;
}

// Area, zero-area triangles, mean edge length and triangles repeated on the same three vertices.
void measure_triangles(const TriMesh& m, const std::vector<Tri>& good, MeshStats& s) {
  double elen = 0;
  for (const Tri& f : good) {
    const Vec3 &a = m.vertices[static_cast<size_t>(f[0])], &b = m.vertices[static_cast<size_t>(f[1])], &c = m.vertices[static_cast<size_t>(f[2])];
    const double area = 0.5 * (b - a).cross(c - a).norm();
    if (!(area > 0)) ++s.degenerate_triangles;
    if (std::isfinite(area)) s.area += area;
    elen += (a - b).norm();  // three additions, in this order: the statistic is unchanged to the bit
    elen += (b - c).norm();
    elen += (c - a).norm();
  }
  if (!good.empty()) s.mean_edge_length = elen / (3.0 * static_cast<double>(good.size()));
  std::vector<Tri> canon;
  const auto order = triangles_by_vertex_set(good, static_cast<Index>(m.vertices.size()), canon);
  for (size_t i = 1; i < order.size(); ++i)
    if (canon[static_cast<size_t>(order[i])] == canon[static_cast<size_t>(order[i - 1])]) ++s.duplicate_triangles;
}

// Edge statistics from the half-edges grouped by undirected edge; the twins of an edge-manifold,
// consistently oriented mesh fall out of the same pass, and so do the connected components.
// Returns the number of edges.
std::int64_t count_edges(const std::vector<Tri>& good, size_t nv, HalfEdges& he, MeshStats& s) {
  const EdgeBuckets eb = half_edges_by_edge(good, static_cast<Index>(nv));
  he.vertex_count = static_cast<Index>(nv);
  assign_huge(he.twin, eb.entries.size(), -1);
  UnionFind comp(static_cast<Index>(good.size()));
  std::int64_t edges = 0;
  auto from = [&](Index h) { return good[static_cast<size_t>(h / 3)][h % 3]; };
  const EdgeBuckets::Entry* e = eb.entries.data();
  for (size_t a = 0; a < nv; ++a)
    for (Index i = eb.start[a], end = eb.start[a + 1]; i < end;) {
      Index j = i + 1;
      while (j < end && e[j].hi == e[i].hi) ++j;
      ++edges;
      if (j - i > 2) ++s.non_manifold_edges;
      if (j - i == 2) {
        if (from(e[i].h) == from(e[i + 1].h)) ++s.inconsistent_edges;
        he.twin[static_cast<size_t>(e[i].h)] = e[i + 1].h;
        he.twin[static_cast<size_t>(e[i + 1].h)] = e[i].h;
      }
      for (Index k = i + 1; k < j; ++k) comp.unite(e[i].h / 3, e[k].h / 3);
      i = j;
    }
  for (Index t = 0; t < static_cast<Index>(good.size()); ++t) s.components += comp.find(t) == t ? 1 : 0;
  return edges;
}

// Non-manifold vertices, boundary loops and the genus, on an edge-manifold, oriented mesh.
void count_loops_and_genus(const std::vector<Tri>& good, size_t nv, const HalfEdges& he, std::int64_t edges, MeshStats& s) {
  auto fans = fans_per_vertex(good, nv, he);
  for (size_t v = 0; v < nv; ++v) s.non_manifold_vertices += fans[v] > 1 ? 1 : 0;
  std::vector<char> seen(he.twin.size(), 0);
  // Boundary cycles: follow boundary half-edges; next boundary half-edge out of b found by
  // rotating around b through twins.
  for (Index h = 0; h < static_cast<Index>(he.twin.size()); ++h) {
    if (he.twin[static_cast<size_t>(h)] >= 0 || seen[static_cast<size_t>(h)]) continue;
    ++s.boundary_loops;
    Index x = h;
    for (size_t guard = 0; guard <= he.twin.size() && !seen[static_cast<size_t>(x)]; ++guard) {
      seen[static_cast<size_t>(x)] = 1;
      Index y = HalfEdges::next(x);
      while (he.twin[static_cast<size_t>(y)] >= 0) y = HalfEdges::next(he.twin[static_cast<size_t>(y)]);
      x = y;
    }
  }
  const std::int64_t V = static_cast<std::int64_t>(nv) - s.isolated_vertices;
  const std::int64_t chi = V - edges + static_cast<std::int64_t>(good.size());
  s.genus = s.non_manifold_vertices ? -1 : (2 * s.components - chi - s.boundary_loops) / 2;
}

}  // namespace

double bbox_diagonal(const TriMesh& m) {
  Vec3 lo, hi;
  bounding_box(m, lo, hi);
  return (hi - lo).norm();
}

MeshStats compute_stats(const TriMesh& m) {
  MeshStats s;
  s.non_finite = bounding_box(m, s.bbox_min, s.bbox_max);
  const std::vector<Tri> good = usable_triangles(m, s);
  measure_triangles(m, good, s);
  HalfEdges he;
  const std::int64_t edges = count_edges(good, m.vertices.size(), he, s);
  // Boundary loops and fans only make sense on an edge-manifold, oriented mesh.
  if (s.non_manifold_edges == 0 && s.inconsistent_edges == 0 && s.bad_indices == 0) count_loops_and_genus(good, m.vertices.size(), he, edges, s);
  else s.genus = -1;
  return s;
}

HalfEdges validate_mesh(const TriMesh& m) {
  const size_t nv = m.vertices.size(), nt = m.triangles.size();
  if (nv < 3 || nt < 1) fail(Errc::invalid_mesh, "a face needs at least 3 vertices and 1 triangle (got " + std::to_string(nv) + " vertices, " + std::to_string(nt) + " triangles)");
  if (nv > 0x7fffffff || nt > 0x7fffffff / 3) fail(Errc::invalid_mesh, "too many vertices or triangles for 32-bit indices");
  for (size_t v = 0; v < nv; ++v)
    if (!m.vertices[v].allFinite())
      fail(Errc::invalid_mesh, "vertex " + std::to_string(v) + " has a NaN or infinite coordinate");
  for (size_t t = 0; t < nt; ++t) {
    const Tri& f = m.triangles[t];
    for (int j = 0; j < 3; ++j)
      if (f[j] < 0 || static_cast<size_t>(f[j]) >= nv)
        fail(Errc::invalid_mesh, tri_str(m, t) + ": vertex index " + std::to_string(f[j]) + " is out of range [0, " + std::to_string(nv) + ")");
    if (f[0] == f[1] || f[1] == f[2] || f[0] == f[2]) fail(Errc::invalid_mesh, tri_str(m, t) + " repeats a vertex");
  }
  // Duplicate triangles are looked for only when the mesh fails a later check, or has two
  // triangles: a duplicate pair either repeats a directed edge (inconsistent or non-manifold edge)
  // or, reversed, closes on itself (a separate component, or the whole mesh if it has two triangles).
  // Its message, the more telling one, still wins; a valid mesh skips the sort and its index
  // array, which grow with the triangle count.
  if (nt <= 2) throw_if_duplicates(m);
  try {
    HalfEdges he = build_halfedges(m.triangles, static_cast<Index>(nv));  // non-manifold edges, orientation
    const Index bad = first_multi_fan_vertex(m.triangles, nv, he);
    if (bad >= 0) {
      const auto fans = fans_per_vertex(m.triangles, nv, he);
      fail(Errc::invalid_mesh, "non-manifold vertex " + std::to_string(bad) + ": its triangles form " + std::to_string(fans[static_cast<size_t>(bad)]) + " separate fans");
    }
    UnionFind comp(static_cast<Index>(nt));
    for (Index h = 0; h < static_cast<Index>(he.twin.size()); ++h)
      if (he.twin[static_cast<size_t>(h)] >= 0) comp.unite(h / 3, he.twin[static_cast<size_t>(h)] / 3);
    for (Index t = 0; t < static_cast<Index>(nt); ++t)
      if (comp.find(t) != 0)
        fail(Errc::invalid_mesh, "the mesh has several connected components (" + tri_str(m, static_cast<size_t>(t)) + " is not connected to triangle 0); flatten each component as its own face");
    return he;
  } catch (const Error&) {
    throw_if_duplicates(m);
    throw;
  }
}

}  // namespace wefm
