#pragma once
// UV -> 3D (METHOD §9.3): point location in the solved UV triangulation through a uniform grid of
// triangle bounding boxes, then barycentric interpolation in the 3D triangle.
#include <vector>

#include "wefm/core/meshing/predicates.hpp"
#include "wefm/core/mesh/topology.hpp"

namespace wefm::meshing {

struct UvHit {
  Index tri = -1;  // -1: p is not finite (nothing to map it through)
  double bary[3] = {0, 0, 0};
  bool inside = false;  // false: p lies outside the domain; bary is the nearest domain point's
};

class UvLocator {
 public:
  UvLocator(const TriMesh& mesh, const Topology& topo, const VectorXc& uv);

  // A point farther than kReach domain diagonals from the domain is located through the point at
  // that distance in its direction, whose squared distances stay finite.
  static constexpr double kReach = 1e6;
  UvHit locate(const P2& p) const;
  // NaN for a hit with no triangle.
  Vec3 to_3d(const UvHit& hit) const;
  P2 corner(Index t, int k) const { return uv_[static_cast<size_t>(3 * t + k)]; }
  // sqrt(3D area / UV area) of triangle t: 3D length per UV length.
  double scale_3d_per_uv(Index t) const { return scale_[static_cast<size_t>(t)]; }
  Index triangle_count() const { return static_cast<Index>(scale_.size()); }

 private:
  P2 within_reach(const P2& p) const;
  void nearest_on_boundary(const P2& p, int ci, int cj, UvHit& hit) const;

  const TriMesh& mesh_;
  std::vector<P2> uv_;  // 3 per triangle
  std::vector<double> scale_;
  P2 lo_, hi_, cell_;
  double reach_ = 0;  // kReach domain diagonals
  int nx_ = 1, ny_ = 1;
  std::vector<Index> start_, items_;
};

}  // namespace wefm::meshing
