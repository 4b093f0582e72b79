#pragma once
// Quality of a layout (METHOD §8) and the distortion figures reported with every solve.
#include "wefm/core/mesh/topology.hpp"

namespace wefm {

struct Quality {
  double score = 0;  // METHOD §8: weighted mean of r^2, -1 with flips, -2 with boundary intersections
  std::int64_t flips = 0;
  std::int64_t boundary_intersections = 0;
  double area_mean = 0, area_max = 0;    // |log(UV area / 3D area)| after normalising total area
  double angle_mean = 0, angle_max = 0;  // sigma_max / sigma_min of the 3D->UV Jacobian
  double uv_area = 0, area_3d = 0;
};

// z holds the UV of every use (any scale). Triangles of zero 3D area are left out of the
// distortion figures but still counted as flips when their UV area is negative. `threads`: the
// per-triangle passes' threads; the figures are the same bits for any count.
Quality evaluate_quality(const TriMesh& mesh, const Topology& topo, const VectorXc& z, int threads = 1);

// Proper crossings between the segments of all loops (segments sharing a use are not tested).
// A uniform grid keeps it near-linear in the number of segments.
std::int64_t count_boundary_intersections(const Topology& topo, const VectorXc& z);

}  // namespace wefm
