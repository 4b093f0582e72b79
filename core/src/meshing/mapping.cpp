#include "wefm/core/meshing/mapping.hpp"

#include <limits>

namespace wefm::meshing {

FaceMapper::FaceMapper(const TriMesh& mesh, const Topology& topo, const VectorXc& uv)
    : mesh_(mesh), topo_(topo), uv_(uv), uv_index_(mesh, topo, uv), xyz_index_(mesh) {}

std::int64_t FaceMapper::uv_to_3d(std::int64_t n, const double* uv, double* xyz, PointStatus* status, Index* tri) const {
  std::int64_t unmapped = 0;
  for (std::int64_t i = 0; i < n; ++i) {
    const UvHit h = uv_index_.locate(P2(uv[2 * i], uv[2 * i + 1]));
    if (xyz) {
      const Vec3 x = uv_index_.to_3d(h);  // NaN without a triangle
      xyz[3 * i] = x.x(), xyz[3 * i + 1] = x.y(), xyz[3 * i + 2] = x.z();
    }
    const PointStatus s = h.tri < 0 ? PointStatus::unmapped : h.inside ? PointStatus::inside : PointStatus::outside;
    unmapped += s == PointStatus::unmapped;
    if (status) status[i] = s;
    if (tri) tri[i] = s == PointStatus::inside ? h.tri : -1;
  }
  return unmapped;
}

std::int64_t FaceMapper::xyz_to_uv(std::int64_t n, const double* xyz, double* uv, PointStatus* status, Index* tri) const {
  const double tol = 1e-6 * xyz_index_.bbox_diagonal();
  std::int64_t unmapped = 0;
  for (std::int64_t i = 0; i < n; ++i) {
    const SurfaceHit h = xyz_index_.closest(Vec3(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]));
    const PointStatus s = h.tri < 0 ? PointStatus::unmapped : h.distance <= tol ? PointStatus::inside : PointStatus::outside;
    unmapped += s == PointStatus::unmapped;
    if (uv) {
      Complex z(std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::quiet_NaN());
      if (h.tri >= 0) {
        z = 0;
        for (size_t k = 0; k < 3; ++k) z += h.bary[k] * uv_[topo_.corner_use[3 * static_cast<size_t>(h.tri) + k]];
      }
      uv[2 * i] = z.real(), uv[2 * i + 1] = z.imag();
    }
    if (status) status[i] = s;
    if (tri) tri[i] = s == PointStatus::inside ? h.tri : -1;
  }
  return unmapped;
}

}  // namespace wefm::meshing
