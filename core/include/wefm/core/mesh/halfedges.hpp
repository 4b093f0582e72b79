#pragma once
// Half-edge connectivity over a triangle soup. Half-edge h = 3t + j runs from corner j to corner
// j+1 of triangle t; the corner opposite it is j+2. Keeping h implicit in the triangle array makes
// corner, half-edge and triangle indices interchangeable without extra storage.
#include <vector>

#include "wefm/core/sys/types.hpp"

namespace wefm {

struct HalfEdges {
  std::vector<Index> twin;  // -1 on the mesh boundary
  Index vertex_count = 0;

  static Index tri(Index h) { return h / 3; }
  static Index next(Index h) { return h - h % 3 + (h % 3 + 1) % 3; }
  static Index prev(Index h) { return h - h % 3 + (h % 3 + 2) % 3; }
  static Index corner_from(Index h) { return h; }            // corner index of the start vertex
  static Index corner_opposite(Index h) { return prev(h); }  // corner index of the opposite vertex
};

// Builds twins; throws invalid_mesh on an edge shared by more than two triangles or two triangles
// traversing an edge the same way (inconsistent orientation). Vertex ids must lie in [0, vertex_count).
HalfEdges build_halfedges(const std::vector<Tri>& triangles, Index vertex_count);

// Half-edge from a to b, or -1. Linear in the valence of a via a vertex->outgoing index, built on
// the first find: a face whose topology names no facet edge never pays for it (an index the size
// of the vertex count plus the half-edges). The triangles must outlive the lookup.
class HalfEdgeLookup {
 public:
  HalfEdgeLookup(const std::vector<Tri>& triangles, Index vertex_count) : tris_(&triangles), vertex_count_(vertex_count) {}
  Index find(Index a, Index b);

 private:
  void build();
  const std::vector<Tri>* tris_;
  Index vertex_count_;
  std::vector<Index> start_, outgoing_;
};

}  // namespace wefm
