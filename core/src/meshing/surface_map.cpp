#include "wefm/core/meshing/surface_map.hpp"

#include <cmath>

namespace wefm::meshing {

SurfaceMap::SurfaceMap(const TriMesh& mesh, const Topology& topo, const VectorXc& uv)
    : mesh_(mesh), loc_(mesh, topo, uv), vnormal_(mesh.vertices.size(), Vec3::Zero()) {
  for (const Tri& t : mesh.triangles) {
    const Vec3 n = (mesh.vertices[static_cast<size_t>(t[1])] - mesh.vertices[static_cast<size_t>(t[0])])
                       .cross(mesh.vertices[static_cast<size_t>(t[2])] - mesh.vertices[static_cast<size_t>(t[0])]);
    for (Index v : t) vnormal_[static_cast<size_t>(v)] += n;
  }
  for (Vec3& n : vnormal_)
    if (n.norm() > 0) n.normalize();
}

bool SurfaceMap::lift(const P2& p, Vec3& xyz, Vec3* normal) const {
  const UvHit hit = loc_.locate(p);
  xyz = loc_.to_3d(hit);
  if (hit.tri < 0) {  // p is not finite: no triangle to take a normal from
    if (normal) *normal = xyz;
    return false;
  }
  if (normal) {
    const Tri& t = mesh_.triangles[static_cast<size_t>(hit.tri)];
    Vec3 n = Vec3::Zero();
    for (int k = 0; k < 3; ++k) n += hit.bary[k] * vnormal_[static_cast<size_t>(t[static_cast<size_t>(k)])];
    *normal = n.norm() > 0 ? n.normalized() : n;
  }
  return hit.inside;
}

bool SurfaceMap::jacobian(const P2& p, Eigen::Matrix<double, 3, 2>& J) const {
  const UvHit hit = loc_.locate(p);
  J.setZero();
  if (hit.tri < 0) return false;
  const Tri& t = mesh_.triangles[static_cast<size_t>(hit.tri)];
  Eigen::Matrix<double, 3, 2> X;
  Eigen::Matrix2d U;
  for (int k = 0; k < 2; ++k) {
    X.col(k) = mesh_.vertices[static_cast<size_t>(t[static_cast<size_t>(k) + 1])] - mesh_.vertices[static_cast<size_t>(t[0])];
    U.col(k) = loc_.corner(hit.tri, k + 1) - loc_.corner(hit.tri, 0);
  }
  const double det = U.determinant();
  if (!(std::fabs(det) > 0) || !std::isfinite(det)) return false;
  J = X * U.inverse();
  return J.allFinite();
}

}  // namespace wefm::meshing
