#pragma once
// Face topology (METHOD §1): edges as vertex chains, loops as ordered edge uses, repeated edges, and
// the vertex uses that are the unknowns. A use is a vertex on one side of the repeated edges through
// it; triangles refer to uses through their corners.
#include <map>
#include <utility>
#include <vector>

#include "wefm/core/mesh/halfedges.hpp"
#include "wefm/core/mesh/trimesh.hpp"

namespace wefm {

struct EdgeUse {
  Index edge = -1;
  bool reversed = false;
};

enum class EdgeMode : int { Auto = 0, Free = 1, Periodic = 2, Scar = 3, Rotational = 4 };

// What the caller said. Empty loops and seams: derive everything from the mesh boundary.
struct TopologySpec {
  std::vector<std::vector<Index>> edges;
  std::vector<std::vector<EdgeUse>> loops;
  std::vector<std::pair<Index, Index>> seams;  // facet edges to cut along (used when loops is empty)
  Index outer_loop = -1;                       // loop id (given loops) or boundary-cycle index; -1 auto
  std::map<Index, EdgeMode> edge_modes;
};

struct RepeatedEdge {
  Index edge = -1;
  std::vector<Index> side_a, side_b;  // uses at chain vertices 0..m; side a holds half-edges v_j -> v_j+1
};

struct Topology {
  HalfEdges he;
  Index use_count = 0;
  std::vector<Index> use_vertex;  // use -> vertex
  std::vector<Index> corner_use;  // 3 per triangle
  std::vector<char> use_on_loop;
  std::vector<std::vector<Index>> edges;
  std::vector<std::vector<EdgeUse>> loops;
  std::vector<std::vector<Index>> loop_uses;  // per loop, in order, the face on the left
  Index outer_loop = 0;
  std::vector<RepeatedEdge> repeated;
  std::vector<Index> edge_repeated;  // per edge: index into repeated, or -1
  bool derived = true;               // edges and loops were derived, not given
};

// Validates the spec against the mesh (which must already pass validate_mesh) and builds uses,
// loops and repeated edges. Throws Error(invalid_topology) naming the edge, loop or facet edge.
// `half_edges`: the mesh's half-edges if already built (validate_mesh returns them), else null.
Topology build_topology(const TriMesh& mesh, const TopologySpec& spec, const HalfEdges* half_edges = nullptr);

// 3D length of a loop (sum of its facet edges).
double loop_length_3d(const TriMesh& mesh, const Topology& topo, Index loop);

}  // namespace wefm
