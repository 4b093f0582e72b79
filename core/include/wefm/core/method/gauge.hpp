#pragma once
// Gauges (METHOD §5, §7): translation through sum eta_i z_i = 0, rotation and scale through the
// vector between two boundary uses. Caller constraints replace the gauges they make redundant.
#include <utility>
#include <vector>

#include "wefm/core/method/coefficients.hpp"
#include "wefm/core/linalg/linear_row.hpp"

namespace wefm {

// The longest facet edge of a loop, as its two consecutive uses (face on the left).
std::pair<Index, Index> longest_loop_segment(const Topology& topo, const TriMesh& mesh, Index loop);

// Two uses of a loop far apart in the layout z (two sweeps of farthest-point search).
std::pair<Index, Index> far_pair(const Topology& topo, const VectorXc& z, Index loop);

struct GaugeChoice {
  bool translation = true;  // add sum eta z = 0
  bool vector = true;       // add z_b - z_a = c
  Complex center{0, 0};     // a point the caller's constraints keep fixed under scaling
};

// Which automatic gauges the caller's rows leave necessary, judged on a reference layout z_ref.
GaugeChoice choose_gauges(const std::vector<LinearRow>& rows, const VectorXc& z_ref);

// Two uses of a loop far apart in 3D. Splitting these off the point block pins the similarity
// mode firmly, which keeps K_PP well conditioned (two adjacent uses would leave it nearly singular).
std::pair<Index, Index> far_pair_3d(const TriMesh& mesh, const Topology& topo, Index loop);

// A rough layout: the 3D positions projected onto their best-fit plane (normalised units).
VectorXc planar_projection(const TriMesh& mesh, const Topology& topo, double length_scale);

}  // namespace wefm
