// Mapping points between a solved face's domain and its 3D triangulation.
#include <string>
#include <vector>

#include "handles.hpp"
#include "wefm/core/meshing/mapping.hpp"

using wefm::capi::guarded;

namespace {

template <class F>
wefm_status map_points(wefm_face* face, int64_t n, int32_t* point_status, int32_t* triangles, F&& run) {
  return guarded(&face->last_error, [&] {
    if (n < 0) throw wefm::Error(wefm::Errc::invalid_argument, "point count " + std::to_string(n) + " is negative");
    const wefm::FlattenResult& r = face->face.result();
    const wefm::meshing::FaceMapper mapper(face->face.mesh(), face->face.topology(), r.uv);
    std::vector<char> inside(static_cast<size_t>(n));
    std::vector<wefm::Index> tri(triangles ? static_cast<size_t>(n) : 0);
    run(mapper, reinterpret_cast<bool*>(inside.data()), triangles ? tri.data() : nullptr);
    for (int64_t i = 0; i < n; ++i) {
      if (point_status) point_status[i] = inside[static_cast<size_t>(i)] ? WEFM_OK : WEFM_ERROR_OUTSIDE_DOMAIN;
      if (triangles) triangles[i] = tri[static_cast<size_t>(i)];
    }
  });
}

}  // namespace

extern "C" {

WEFM_API wefm_status wefm_face_map_uv_to_3d(wefm_face* face, int64_t n, const double* uv, double* xyz, int32_t* point_status, int32_t* triangles) {
  WEFM_REQUIRE(face, "wefm_face_map_uv_to_3d");
  WEFM_REQUIRE(uv, "wefm_face_map_uv_to_3d");
  WEFM_REQUIRE(xyz, "wefm_face_map_uv_to_3d");
  return map_points(face, n, point_status, triangles, [&](const wefm::meshing::FaceMapper& m, bool* in, wefm::Index* t) { m.uv_to_3d(n, uv, xyz, in, t); });
}

WEFM_API wefm_status wefm_face_map_3d_to_uv(wefm_face* face, int64_t n, const double* xyz, double* uv, int32_t* point_status, int32_t* triangles) {
  WEFM_REQUIRE(face, "wefm_face_map_3d_to_uv");
  WEFM_REQUIRE(xyz, "wefm_face_map_3d_to_uv");
  WEFM_REQUIRE(uv, "wefm_face_map_3d_to_uv");
  return map_points(face, n, point_status, triangles, [&](const wefm::meshing::FaceMapper& m, bool* in, wefm::Index* t) { m.xyz_to_uv(n, xyz, uv, in, t); });
}

}
