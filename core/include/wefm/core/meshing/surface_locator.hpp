#pragma once
// 3D -> UV (METHOD §9.3): closest point on the 3D triangulation through a uniform grid of triangle
// bounding boxes, searched in growing shells until no closer triangle can exist.
#include <vector>

#include "wefm/core/mesh/topology.hpp"

namespace wefm::meshing {

struct SurfaceHit {
  Index tri = -1;  // -1: p is not finite or the mesh has no triangles
  double bary[3] = {0, 0, 0};
  double distance = 0;
};

class SurfaceLocator {
 public:
  explicit SurfaceLocator(const TriMesh& mesh);
  // A point farther than kReach bounding-box diagonals from the mesh is searched from the point at
  // that distance in its direction, whose squared distances stay finite; `distance` is its own.
  static constexpr double kReach = 1e6;
  SurfaceHit closest(const Vec3& p) const;
  double bbox_diagonal() const { return diag_; }

 private:
  Vec3 within_reach(const Vec3& p) const;

  const TriMesh& mesh_;
  Vec3 lo_ = Vec3::Zero(), centre_ = Vec3::Zero();
  double cell_ = 1, diag_ = 0;
  int n_[3] = {1, 1, 1};
  std::vector<Index> start_, items_;
};

// Closest point of triangle (a, b, c) to p, as barycentric coordinates (Ericson, RTCD §5.1.5).
void closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c, double bary[3]);

}  // namespace wefm::meshing
