#pragma once
// Facet edges and triangles in the order a sort by their vertex ids would give, found by a counting
// sort on the smallest vertex id (linear in the mesh) and a sort of each small bucket. Validation,
// mesh statistics and the half-edge build group equal keys this way; the order is the one the
// comparison sorts they replace produced, so the first offender named in a message is unchanged.
#include <vector>

#include "wefm/core/sys/types.hpp"

namespace wefm {

// Half-edges by undirected edge (lo, hi), lo < hi: the half-edges whose smaller vertex is lo are
// entries[start[lo] .. start[lo + 1]), sorted by (hi, h). Equal hi in a bucket: one facet edge.
struct EdgeBuckets {
  struct Entry {
    Index hi, h;  // h = 3t + j runs from corner j to corner j+1 of triangle t
  };
  std::vector<Index> start;
  std::vector<Entry> entries;
};

// Triangle vertex ids must lie in [0, vertex_count).
EdgeBuckets half_edges_by_edge(const std::vector<Tri>& triangles, Index vertex_count);

// Triangle indices sorted by (sorted vertex triple, index); `canon` receives each triangle's
// sorted triple. Equal neighbours use the same three vertices.
std::vector<Index> triangles_by_vertex_set(const std::vector<Tri>& triangles, Index vertex_count, std::vector<Tri>& canon);

}  // namespace wefm
