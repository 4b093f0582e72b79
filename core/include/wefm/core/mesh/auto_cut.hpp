#pragma once
// Automatic cuts (wefm_options.auto_cut): the facet edges along which a face that cannot be
// flattened as given is cut open, so that build_topology turns them into one repeated edge.
//   annulus (two boundary cycles): the shortest path in 3D between the two cycles;
//   closed genus 0: a slit (docs/SOLVER.md, "Automatic cuts", has the measurements behind the rule).
// Any other face needs no cut. Deterministic (ties broken by vertex index), O(n log n).
#include <utility>
#include <vector>

#include "wefm/core/mesh/trimesh.hpp"

namespace wefm {

enum class AutoCutKind { None = 0, Annulus = 1, Closed = 2 };

// How a closed surface's slit is chosen. Only SharpThenFarthest is used by the solver; the others
// stay for the measurement that chose it (tests and docs/SOLVER.md).
enum class SlitRule {
  SharpThenFarthest = 0,  // through the cone vertices (|angle deficit| > 30 deg), else FarthestPair
  FarthestPair = 1,       // geodesic between the two ends of a double Dijkstra sweep
  ShortestEdge = 2,       // one facet edge: the sphere-with-a-small-hole layout
};

struct AutoCut {
  AutoCutKind kind = AutoCutKind::None;
  std::vector<std::pair<Index, Index>> seams;  // facet edges in path order
  double length = 0;                           // 3D length of the cut
};

// The mesh must pass validate_mesh. Throws Error(invalid_topology) for a closed surface of genus > 0
// (how many handles; seams are needed) and for an annulus whose cycles cannot be joined.
AutoCut compute_auto_cut(const TriMesh& mesh, SlitRule rule = SlitRule::SharpThenFarthest);

}  // namespace wefm
