#pragma once
// Facet edges and triangles in the order a sort by their vertex ids would give, found by a counting
// sort on the smallest vertex id (linear in the mesh) and a sort of each small bucket. Validation,
// mesh statistics and the half-edge build group equal keys this way; the order is the one the
// comparison sorts they replace produced, so the first offender named in a message is unchanged.
#include <vector>

#include "wefm/core/types.hpp"

namespace wefm {

// Half-edge h = 3t + j (corner j to j+1 of triangle t) as its undirected edge lo < hi.
struct EdgeKey {
  Index lo, hi, h;
};

// Every half-edge sorted by (lo, hi, h); equal (lo, hi) are the half-edges of one facet edge.
// Triangle vertex ids must lie in [0, vertex_count).
std::vector<EdgeKey> half_edges_by_edge(const std::vector<Tri>& triangles, Index vertex_count);

// Triangle indices sorted by (sorted vertex triple, index); `canon` receives each triangle's
// sorted triple. Equal neighbours use the same three vertices.
std::vector<Index> triangles_by_vertex_set(const std::vector<Tri>& triangles, Index vertex_count, std::vector<Tri>& canon);

}  // namespace wefm
