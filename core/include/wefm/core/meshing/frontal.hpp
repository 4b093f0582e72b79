#pragma once
// Frontal-Delaunay point placement (Rebay, J. Comput. Phys. 106, 1993), measured on the surface.
// Triangles are accepted once their 3D circumradius is near that of the equilateral triangle of the
// local size; the largest triangle next to an accepted one (or to the boundary) gets a new node on
// the perpendicular bisector of that shared "front" edge, at the distance that makes the triangle
// it forms with the edge equilateral of the local size in 3D, never past its own circumcentre
// (the Voronoi segment, so the node keeps its distance from every other node). Distances along
// the bisector are taken in the surface's first fundamental form at the edge midpoint, so UV
// scale and anisotropy of the domain do not show in 3D. The front advances from the boundary and
// leaves rows of near-equilateral elements, where circumcentre refinement leaves scattered ones.
#include <cstdint>
#include <functional>
#include <vector>

#include "wefm/core/meshing/size_field.hpp"
#include "wefm/core/meshing/surface_map.hpp"
#include "wefm/core/meshing/triangulation.hpp"

namespace wefm::meshing {

struct FrontalSettings {
  // A triangle is accepted when circumradius * sqrt(3) / size is below this (1 = equilateral of
  // side `size`).
  double accept_ratio = 1.3;
  std::int64_t max_nodes = 0;  // stop at this many nodes (0 = no cap)
};

// `xyz` and `node_size` hold the 3D point and target size of every node of `tr` and grow with it.
// `tick` is called after every insertion (cancellation). Returns the number of nodes inserted.
std::int64_t frontal_refine(Triangulation& tr, std::vector<Vec3>& xyz, std::vector<double>& node_size, const SurfaceMap& map,
                            const SizeField& size, const FrontalSettings& settings, const std::function<void()>& tick);

// sqrt(3) * circumradius / size of the 3D triangle (a, b, c): 1 for the equilateral of side `size`.
double size_ratio(const Vec3& a, const Vec3& b, const Vec3& c, double size);

}  // namespace wefm::meshing
