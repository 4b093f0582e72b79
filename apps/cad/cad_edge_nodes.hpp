#pragma once
// The first step of whole-model meshing (the paper's §1.2): every model edge is discretised once in
// 3D, so the faces sharing it get the very same nodes and the face meshes conform. Nodes are placed
// at equal arc length along the edge's facet chain, so they lie on the chain as
// wefm_face_set_edge_nodes requires; the chain is the same polyline in every face that uses the edge
// (BRepMesh discretises an edge once for the whole model).
#include <map>
#include <vector>

#include "cad_model.hpp"

namespace wefm_cad {

struct EdgeNodes {
  std::vector<double> xyz;  // 3 per node, in the edge's direction, both end vertices included
};

// Local size per face (by CadModel::faces index): a face narrower than h gets its width, so it has
// about one element across instead of elements stretched over it. Width = 2 area / perimeter (the
// width of a long strip, the radius of a disk). Floored at h / 4: a needle face cannot ask for
// millions of elements along its long edges, and the faces next to a narrow face (meshed at h
// inside) grade down at most 4:1 along the shared edge; at 16:1 they came out worse than with no
// local size at all (Ball.brep).
std::vector<double> local_face_sizes(const CadModel& model, double h);

// The area of a face's tessellation.
double face_area(const CadFace& face);

// Per model edge id: its nodes (at least one segment; at least three for a closed edge, so a circle
// stays a polygon) at the smallest size of the faces that use it (`face_sizes`, one per face, or
// empty for h everywhere). Degenerate edges get no entry. With `gradation` g > 0 the segments of
// an edge shrink towards a model vertex where another edge has shorter ones, growing back by g per
// unit length (1 + g per segment, roughly); 0 keeps them uniform.
std::map<long long, EdgeNodes> discretise_model_edges(const CadModel& model, double h,
                                                      const std::vector<double>& face_sizes = {}, double gradation = 0);

}  // namespace wefm_cad
