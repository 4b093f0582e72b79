#pragma once
// Vectorised mapping between a solved face's domain and its 3D triangulation (wefm_face_map_*).
#include <cstdint>

#include "wefm/core/meshing/surface_locator.hpp"
#include "wefm/core/meshing/uv_locator.hpp"

namespace wefm::meshing {

class FaceMapper {
 public:
  FaceMapper(const TriMesh& mesh, const Topology& topo, const VectorXc& uv);

  // Per point: `inside[i]` false when the point lies outside the domain (UV) or farther than
  // 1e-6 of the bounding box diagonal from the triangulation (3D); it is mapped through the
  // nearest point all the same. `tri` gets the triangle used. Output arrays may be null.
  void uv_to_3d(std::int64_t n, const double* uv, double* xyz, bool* inside, Index* tri) const;
  void xyz_to_uv(std::int64_t n, const double* xyz, double* uv, bool* inside, Index* tri) const;

 private:
  const TriMesh& mesh_;
  const Topology& topo_;
  const VectorXc& uv_;
  UvLocator uv_index_;
  SurfaceLocator xyz_index_;
};

}  // namespace wefm::meshing
