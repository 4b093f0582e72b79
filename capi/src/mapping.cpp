// Mapping points between a solved face's domain and its 3D triangulation.
#include <algorithm>
#include <string>

#include "handles.hpp"
#include "wefm/core/meshing/mapping.hpp"

using wefm::capi::Access;
using wefm::capi::on_face;
using wefm::meshing::PointStatus;

namespace {

wefm_status to_status(PointStatus s) {
  switch (s) {
    case PointStatus::inside: return WEFM_OK;
    case PointStatus::outside: return WEFM_ERROR_OUTSIDE_DOMAIN;
    case PointStatus::unmapped: break;
  }
  return WEFM_ERROR_INVALID_ARGUMENT;
}

// Maps the points in blocks (no allocation grows with n) through run(mapper, first, count, status,
// tri), which returns how many of them it could not map. Every point gets its per-point status;
// the call fails with WEFM_ERROR_INVALID_ARGUMENT when any point was not finite.
template <class F>
wefm_status map_points(wefm_face* face, const char* function, int64_t n, int32_t* point_status, int32_t* triangles, F&& run) {
  return on_face(face, Access::read, function, [&] {
    if (n < 0) throw wefm::Error(wefm::Errc::invalid_argument, "point count " + std::to_string(n) + " is negative");
    const wefm::FlattenResult& r = face->face.result();
    const wefm::meshing::FaceMapper mapper(face->face.mesh(), face->face.topology(), r.uv);
    constexpr int64_t block = 1024;
    PointStatus status[block];
    wefm::Index tri[block];
    int64_t unmapped = 0, first_unmapped = -1;
    for (int64_t i0 = 0; i0 < n; i0 += block) {
      const int64_t m = std::min(block, n - i0);
      const int64_t bad = run(mapper, i0, m, status, triangles ? tri : nullptr);
      for (int64_t k = 0; k < m; ++k) {
        if (point_status) point_status[i0 + k] = to_status(status[k]);
        if (triangles) triangles[i0 + k] = tri[k];
        if (status[k] == PointStatus::unmapped && first_unmapped < 0) first_unmapped = i0 + k;
      }
      unmapped += bad;
    }
    if (unmapped > 0)
      throw wefm::Error(wefm::Errc::invalid_argument,
                        std::to_string(unmapped) + " of " + std::to_string(n) + " points have a NaN or infinite coordinate (the first: point " +
                            std::to_string(first_unmapped) + "): their outputs are NaN, their point_status WEFM_ERROR_INVALID_ARGUMENT; the other points are mapped");
  });
}

}  // namespace

extern "C" {

WEFM_API wefm_status wefm_face_map_uv_to_3d(wefm_face* face, int64_t n, const double* uv, double* xyz, int32_t* point_status, int32_t* triangles) {
  WEFM_REQUIRE(face, "wefm_face_map_uv_to_3d");
  WEFM_REQUIRE(uv, "wefm_face_map_uv_to_3d");
  WEFM_REQUIRE(xyz, "wefm_face_map_uv_to_3d");
  return map_points(face, "wefm_face_map_uv_to_3d", n, point_status, triangles, [&](const wefm::meshing::FaceMapper& m, int64_t i0, int64_t k, PointStatus* s, wefm::Index* t) {
    return m.uv_to_3d(k, uv + 2 * i0, xyz + 3 * i0, s, t);
  });
}

WEFM_API wefm_status wefm_face_map_3d_to_uv(wefm_face* face, int64_t n, const double* xyz, double* uv, int32_t* point_status, int32_t* triangles) {
  WEFM_REQUIRE(face, "wefm_face_map_3d_to_uv");
  WEFM_REQUIRE(xyz, "wefm_face_map_3d_to_uv");
  WEFM_REQUIRE(uv, "wefm_face_map_3d_to_uv");
  return map_points(face, "wefm_face_map_3d_to_uv", n, point_status, triangles, [&](const wefm::meshing::FaceMapper& m, int64_t i0, int64_t k, PointStatus* s, wefm::Index* t) {
    return m.xyz_to_uv(k, xyz + 3 * i0, uv + 2 * i0, s, t);
  });
}

}
