#pragma once
// Per half-edge WEFM coefficients from the 3D geometry alone (METHOD §2), in units where the mean
// 3D edge length is 1 so that every weight means the same at any model scale.
#include <vector>

#include "wefm/core/mesh/topology.hpp"

namespace wefm {

struct Coefficients {
  double length_scale = 1.0;        // mean 3D edge length: positions are divided by it
  std::vector<double> alpha;        // per half-edge: foot of the altitude along the base
  std::vector<double> beta;         // per half-edge: altitude / base, times f(I3), floored at min_beta
  std::vector<double> length;       // per half-edge: 3D base length (normalised)
  std::vector<double> corner_angle; // per corner: 3D angle
  std::vector<double> use_angle;    // per use: sum of its 3D corner angles (Theta)
  std::vector<double> use_area;     // per use: 3D area of its triangles (normalised), eta of the gauge
  std::vector<double> tri_area;     // per triangle (normalised)
  Index floored = 0;                // half-edges whose beta was raised to min_beta
  Index degenerate_triangles = 0;   // triangles with zero area
};

// `threads` (Options::threads; <= 1 runs in the caller's thread) splits the work; the result is
// bit-identical for every thread count (see parallel.hpp).
Coefficients compute_coefficients(const TriMesh& mesh, const Topology& topo, bool curvature_adjust, double min_beta,
                                  int threads = 1);

}  // namespace wefm
