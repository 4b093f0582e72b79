#pragma once
// 3D -> UV (METHOD §9): closest point on the 3D triangulation through a uniform grid of triangle
// bounding boxes, searched in growing shells until no closer triangle can exist.
#include <vector>

#include "wefm/core/topology.hpp"

namespace wefm::meshing {

struct SurfaceHit {
  Index tri = -1;
  double bary[3] = {0, 0, 0};
  double distance = 0;
};

class SurfaceLocator {
 public:
  explicit SurfaceLocator(const TriMesh& mesh);
  SurfaceHit closest(const Vec3& p) const;
  double bbox_diagonal() const { return diag_; }

 private:
  const TriMesh& mesh_;
  Vec3 lo_ = Vec3::Zero();
  double cell_ = 1, diag_ = 0;
  int n_[3] = {1, 1, 1};
  std::vector<Index> start_, items_;
};

// Closest point of triangle (a, b, c) to p, as barycentric coordinates (Ericson, RTCD §5.1.5).
void closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, double bary[3]);

}  // namespace wefm::meshing
