#pragma once
// Vectorised mapping between a solved face's domain and its 3D triangulation (wefm_face_map_*).
#include <cstdint>

#include "wefm/core/meshing/surface_locator.hpp"
#include "wefm/core/meshing/uv_locator.hpp"

namespace wefm::meshing {

// What happened to one point.
enum class PointStatus : std::int8_t {
  inside,   // in the domain (UV) or on the triangulation (3D)
  outside,  // mapped through the nearest point of the domain or triangulation
  unmapped  // not finite: the outputs are NaN and the triangle -1
};

class FaceMapper {
 public:
  FaceMapper(const TriMesh& mesh, const Topology& topo, const VectorXc& uv);

  // Per point: `status[i]` is outside when the point lies outside the domain (UV) or farther than
  // 1e-6 of the bounding box diagonal from the triangulation (3D); it is mapped through the
  // nearest point all the same. `tri` gets the triangle used (-1 unless inside). Output arrays
  // may be null. Returns the number of unmapped points.
  std::int64_t uv_to_3d(std::int64_t n, const double* uv, double* xyz, PointStatus* status, Index* tri) const;
  std::int64_t xyz_to_uv(std::int64_t n, const double* xyz, double* uv, PointStatus* status, Index* tri) const;

 private:
  const TriMesh& mesh_;
  const Topology& topo_;
  const VectorXc& uv_;
  UvLocator uv_index_;
  SurfaceLocator xyz_index_;
};

}  // namespace wefm::meshing
