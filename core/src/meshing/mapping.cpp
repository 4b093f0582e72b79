#include "wefm/core/meshing/mapping.hpp"

namespace wefm::meshing {

FaceMapper::FaceMapper(const TriMesh& mesh, const Topology& topo, const VectorXc& uv)
    : mesh_(mesh), topo_(topo), uv_(uv), uv_index_(mesh, topo, uv), xyz_index_(mesh) {}

void FaceMapper::uv_to_3d(std::int64_t n, const double* uv, double* xyz, bool* inside, Index* tri) const {
  for (std::int64_t i = 0; i < n; ++i) {
    const UvHit h = uv_index_.locate(P2(uv[2 * i], uv[2 * i + 1]));
    if (xyz) {
      const Vec3 x = uv_index_.to_3d(h);
      xyz[3 * i] = x.x(), xyz[3 * i + 1] = x.y(), xyz[3 * i + 2] = x.z();
    }
    if (inside) inside[i] = h.inside;
    if (tri) tri[i] = h.inside ? h.tri : -1;
  }
}

void FaceMapper::xyz_to_uv(std::int64_t n, const double* xyz, double* uv, bool* inside, Index* tri) const {
  const double tol = 1e-6 * xyz_index_.bbox_diagonal();
  for (std::int64_t i = 0; i < n; ++i) {
    const SurfaceHit h = xyz_index_.closest(Vec3(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]));
    if (uv) {
      Complex z = 0;
      for (size_t k = 0; k < 3; ++k) z += h.bary[k] * uv_[topo_.corner_use[3 * static_cast<size_t>(h.tri) + k]];
      uv[2 * i] = z.real(), uv[2 * i + 1] = z.imag();
    }
    const bool on = h.distance <= tol;
    if (inside) inside[i] = on;
    if (tri) tri[i] = on ? h.tri : -1;
  }
}

}  // namespace wefm::meshing
