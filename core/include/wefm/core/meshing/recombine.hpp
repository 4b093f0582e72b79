#pragma once
// Quads from a free triangle mesh of the domain (METHOD §9.5): pairs of triangles across an edge
// become quads where the quad is good in 3D, chosen as a large matching of the triangles' dual
// graph; then, for all-quad meshes, every element is split into quads at its edge midpoints and
// centre. The quads are judged in 3D, where they will be used, and kept convex in UV, where the
// mesh lives.
#include "wefm/core/meshing/domain_mesh.hpp"
#include "wefm/core/meshing/surface_map.hpp"

namespace wefm::meshing {

// Turns the triangles of `m` (nodes_per_element 3) into quads where two triangles sharing an edge
// inside the face (not a hard edge) make a quad convex in UV with a 3D scaled Jacobian of at least `min_quality`.
// Afterwards nodes_per_element is 4 and a triangle left over has -1 as its fourth node. The nodes
// are not moved (smooth_quads does that, inside the face only).
void recombine(DomainMesh& m, double min_quality);

// Moves the nodes inside the face (from boundary_nodes on) of a quad-dominant or all-quad mesh
// towards the mean of their neighbours in UV, `passes` times, each move kept only where the worst
// element around the node gets no worse and the elements round it better on the whole (scaled
// Jacobian of quads, Lo lambda of triangles, in 3D; quads kept convex in UV; with `for_mean`, quads
// at scaled Jacobian 0.3 or more kept there, even where a triangle is the worst). With `for_mean`, then
// a few passes of compass moves for the elements' geometric mean, the worst around each node no
// worse: for quad-dominant meshes; an all-quad mesh has four times the nodes for less gain.
void smooth_quads(DomainMesh& m, const SurfaceMap& map, int passes, bool for_mean);

// Where split_into_quads puts a new node inside the face: at the UV middle of its edge or element,
// lifted; or at the UV point (on its edge's UV segment for an edge's middle) whose lift is nearest
// the 3D midpoint of the edge or the 3D mean of the element's corners, as long as the element's
// quads stay convex in UV. The UV middles lift far from those where the flattening stretches
// unevenly across the element (a pinch of the face, sliver facets), and the quads there fold.
enum class SplitNodes { uv_middles, nearest_3d };

// Splits every element of `m` (nodes_per_element 4, triangles with -1 as fourth node) into quads:
// a quad into four, a triangle into three, at the midpoints of its edges and its centre. Inside
// the face a new node is placed as `place` says; on the boundary, at the midpoint of the 3D chord,
// so two faces given the same nodes on an edge still share them. Nodes 0..boundary_nodes-1 stay the
// boundary's, now with its midpoints and the hard edges' (3D chord midpoints too, fixed like the
// boundary's); each hard edge becomes its two halves.
void split_into_quads(DomainMesh& m, const SurfaceMap& map, SplitNodes place);

// The number of quads split_into_quads makes of `m`: a quad's four, a triangle's three.
size_t split_count(const DomainMesh& m);

// All-quad: split_into_quads with the new nodes nearest their 3D targets, then smooth_quads
// (`passes`, not for the mean). Where an element is left below `floor` (a scaled Jacobian; -1 for a quad not convex
// in UV), the split at the UV middles is smoothed too, and the one with the better worst element
// kept: each placement leaves folds on faces where the other leaves none.
void split_and_smooth(DomainMesh& m, const SurfaceMap& map, int passes, double floor);

}  // namespace wefm::meshing
