#pragma once
// Repairs of an imported face whose boundary touches itself at a vertex. A B-rep face can be pinched:
// an inner wire that meets the outer wire (or another inner wire) at a vertex, or two lobes of a hole
// that meet on a periodic face's seam. Its facets then form two or more separate fans around that
// vertex, which no flattener accepts. The 3D surface is the same with the vertex split into one
// vertex per fan (the copies stay at the same point, so the model mesh is welded there again), and
// the loops then are the boundary cycles of the split mesh, walked along the face's edge chains.
#include <string>

#include "cad_model.hpp"

namespace wefm_cad {

// Splits every vertex of face.triangles whose triangles form more than one fan (across edges of two
// triangles) into one vertex per fan, moves each edge chain onto the copies its facets use, and, when
// a vertex was split, replaces the loops by the boundary cycles of the split mesh (seam chains walked
// on both sides, degenerate edges where the walk passes their vertex) and the outer loop by the
// cycle holding the old outer loop's first edge use. Returns the number of vertices added; on a face
// it cannot repair (an open facet edge off every chain, an edge chain the cycles do not cover whole)
// it sets face.error and returns -1.
int split_pinched_vertices(CadFace& face);

}  // namespace wefm_cad
