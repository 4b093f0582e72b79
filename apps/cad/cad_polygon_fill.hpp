#pragma once
// Triangles filling a simple polygon, for a face whose BRepMesh facets do not reach its boundary
// (BRepMesh can give up on a face and leave one facet among its boundary nodes): the face's one
// boundary loop, in the surface's parameters, is filled by ear clipping. The flattener and the
// domain mesher only need facets that cover the face along its edges; their shape is remeshed.
#include <array>
#include <vector>

namespace wefm_cad {

// Triangles (indices into `polygon`) covering a simple polygon given in either turning sense, each
// counter-clockwise. Empty when the polygon has fewer than 3 points. A polygon that crosses itself
// is still covered as a disk, with facets folded over each other where it crosses.
std::vector<std::array<int, 3>> fill_polygon(const std::vector<std::array<double, 2>>& polygon);

}  // namespace wefm_cad
