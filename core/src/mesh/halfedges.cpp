#include "wefm/core/mesh/halfedges.hpp"
#include "wefm/core/sys/huge_pages.hpp"

#include <string>

#include "wefm/core/sys/error.hpp"
#include "wefm/core/mesh/vertex_buckets.hpp"

namespace wefm {

HalfEdges build_halfedges(const std::vector<Tri>& triangles, Index vertex_count) {
  const Index nh = static_cast<Index>(triangles.size() * 3);
  HalfEdges he;
  he.vertex_count = vertex_count;
  assign_huge(he.twin, static_cast<size_t>(nh), -1);
  // Half-edges grouped by undirected edge (counting sort on the smaller vertex): partners adjacent,
  // edges in (lo, hi) order, so the first offending edge is the one a full sort would find.
  const EdgeBuckets eb = half_edges_by_edge(triangles, vertex_count);
  auto from = [&](Index h) { return triangles[static_cast<size_t>(h / 3)][h % 3]; };
  for (Index a = 0; a < vertex_count; ++a) {
    const EdgeBuckets::Entry* e = eb.entries.data();
    for (Index i = eb.start[static_cast<size_t>(a)], end = eb.start[static_cast<size_t>(a) + 1]; i < end;) {
      Index j = i + 1;
      while (j < end && e[j].hi == e[i].hi) ++j;
      const Index b = e[i].hi;
      if (j - i > 2)
        fail(Errc::invalid_mesh, "non-manifold edge (" + std::to_string(a) + ", " + std::to_string(b) + "): shared by " +
                                     std::to_string(j - i) + " triangles (e.g. " + std::to_string(e[i].h / 3) + ", " +
                                     std::to_string(e[i + 1].h / 3) + ", " + std::to_string(e[i + 2].h / 3) + ")");
      if (j - i == 2) {
        const Index h0 = e[i].h, h1 = e[i + 1].h;
        if (from(h0) == from(h1))
          fail(Errc::invalid_mesh, "inconsistent triangle orientation: triangles " + std::to_string(h0 / 3) + " and " +
                                       std::to_string(h1 / 3) + " both traverse edge (" + std::to_string(from(h0)) + ", " +
                                       std::to_string(from(h0) == a ? b : a) + ") the same way");
        he.twin[static_cast<size_t>(h0)] = h1;
        he.twin[static_cast<size_t>(h1)] = h0;
      }
      i = j;
    }
  }
  return he;
}

void HalfEdgeLookup::build() {
  const std::vector<Tri>& triangles = *tris_;
  start_.assign(static_cast<size_t>(vertex_count_) + 1, 0);
  for (const Tri& t : triangles)
    for (Index v : t) ++start_[static_cast<size_t>(v) + 1];
  for (size_t i = 1; i < start_.size(); ++i) start_[i] += start_[i - 1];
  assign_huge(outgoing_, triangles.size() * 3);
  std::vector<Index> fill(start_.begin(), start_.end() - 1);
  for (Index h = 0; h < static_cast<Index>(triangles.size() * 3); ++h)
    outgoing_[static_cast<size_t>(fill[static_cast<size_t>(triangles[static_cast<size_t>(h / 3)][h % 3])]++)] = h;
}

Index HalfEdgeLookup::find(Index a, Index b) {
  if (start_.empty()) build();
  if (a < 0 || b < 0 || static_cast<size_t>(a) + 1 >= start_.size()) return -1;
  for (Index k = start_[static_cast<size_t>(a)]; k < start_[static_cast<size_t>(a) + 1]; ++k) {
    const Index h = outgoing_[static_cast<size_t>(k)];
    if ((*tris_)[static_cast<size_t>(h / 3)][(h % 3 + 1) % 3] == b) return h;
  }
  return -1;
}

}  // namespace wefm
