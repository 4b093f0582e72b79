#pragma once
// The solved domain as a map UV -> surface: 3D point and smooth normal (area-weighted vertex
// normals interpolated barycentrically) at any UV point.
#include "wefm/core/meshing/uv_locator.hpp"

namespace wefm::meshing {

class SurfaceMap {
 public:
  SurfaceMap(const TriMesh& mesh, const Topology& topo, const VectorXc& uv);
  // False when p lies outside the domain; xyz is then the nearest domain point's image (NaN, and
  // the normal too, when p is not finite).
  bool lift(const P2& p, Vec3& xyz, Vec3* normal = nullptr) const;
  // Derivative of the map at p (columns d xyz / du, d xyz / dv) on the facet holding p, or the
  // nearest one outside. False for a degenerate facet: J is then zero.
  bool jacobian(const P2& p, Eigen::Matrix<double, 3, 2>& J) const;
  const UvLocator& locator() const { return loc_; }

 private:
  const TriMesh& mesh_;
  UvLocator loc_;
  std::vector<Vec3> vnormal_;
};

}  // namespace wefm::meshing
