// Face lifecycle, mesh and options.
#include "options_convert.hpp"

using wefm::capi::Access;
using wefm::capi::guarded;
using wefm::capi::on_face;

namespace {

template <class I>
wefm_status set_mesh_impl(wefm_face* face, const char* function, int64_t nv, const double* xyz, int64_t nt, const I* tri) {
  return on_face(face, Access::change, function, [&] {
    if (nv < 0 || nt < 0) throw wefm::Error(wefm::Errc::invalid_argument, "negative vertex or triangle count");
    if (nv > 0x7fffffff || nt > 0x7fffffff / 3) throw wefm::Error(wefm::Errc::invalid_mesh, "too many vertices or triangles for 32-bit indices");
    wefm::TriMesh m;
    m.vertices.resize(static_cast<size_t>(nv));
    for (int64_t v = 0; v < nv; ++v) m.vertices[static_cast<size_t>(v)] = wefm::Vec3(xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]);
    m.triangles.resize(static_cast<size_t>(nt));
    for (int64_t t = 0; t < nt; ++t)
      for (int j = 0; j < 3; ++j) {
        const I v = tri[3 * t + j];
        if (v < 0 || static_cast<int64_t>(v) >= nv)
          throw wefm::Error(wefm::Errc::invalid_mesh, "triangle " + std::to_string(t) + ": vertex index " + std::to_string(v) + " is out of range [0, " + std::to_string(nv) + ")");
        m.triangles[static_cast<size_t>(t)][j] = static_cast<wefm::Index>(v);
      }
    face->face.set_mesh(std::move(m));
  });
}

}  // namespace

extern "C" {

WEFM_API wefm_status wefm_face_create(wefm_face** out) {
  WEFM_REQUIRE(out, "wefm_face_create");
  *out = nullptr;
  return guarded(nullptr, [&] { *out = new wefm_face; });
}

WEFM_API wefm_status wefm_face_retain(wefm_face* face) {
  WEFM_REQUIRE(face, "wefm_face_retain");
  face->refs.fetch_add(1);
  return WEFM_OK;
}

WEFM_API void wefm_face_release(wefm_face* face) {
  // From inside the face's own progress callback the last reference is not freed under the solve:
  // wefm_face_solve frees it when it returns.
  if (face && face->refs.fetch_sub(1) == 1 && !face->solving) delete face;
}

WEFM_API const char* wefm_face_last_error(const wefm_face* face) {
  if (!face) return "wefm_face_last_error: face is NULL";
  return face->last_error.c_str();
}

WEFM_API wefm_status wefm_face_set_mesh(wefm_face* face, int64_t nv, const double* xyz, int64_t nt, const int32_t* tri) {
  WEFM_REQUIRE(face, "wefm_face_set_mesh");
  WEFM_REQUIRE(xyz, "wefm_face_set_mesh");
  WEFM_REQUIRE(tri, "wefm_face_set_mesh");
  return set_mesh_impl(face, "wefm_face_set_mesh", nv, xyz, nt, tri);
}

WEFM_API wefm_status wefm_face_set_mesh_i64(wefm_face* face, int64_t nv, const double* xyz, int64_t nt, const int64_t* tri) {
  WEFM_REQUIRE(face, "wefm_face_set_mesh_i64");
  WEFM_REQUIRE(xyz, "wefm_face_set_mesh_i64");
  WEFM_REQUIRE(tri, "wefm_face_set_mesh_i64");
  return set_mesh_impl(face, "wefm_face_set_mesh_i64", nv, xyz, nt, tri);
}

WEFM_API wefm_status wefm_face_set_mesh_from(wefm_face* face, const wefm_mesh* mesh) {
  WEFM_REQUIRE(face, "wefm_face_set_mesh_from");
  WEFM_REQUIRE(mesh, "wefm_face_set_mesh_from");
  return on_face(face, Access::change, "wefm_face_set_mesh_from", [&] { face->face.set_mesh(mesh->mesh); });
}

WEFM_API wefm_status wefm_face_set_options(wefm_face* face, const wefm_options* options) {
  WEFM_REQUIRE(face, "wefm_face_set_options");
  WEFM_REQUIRE(options, "wefm_face_set_options");
  return on_face(face, Access::change, "wefm_face_set_options", [&] {
    wefm::capi::check_struct_size(options->struct_size, "wefm_options");
    const wefm_options c = wefm::capi::read_versioned(options, wefm::capi::to_c(wefm::Options{}));
    face->face.set_options(wefm::capi::from_c(c));
  });
}

WEFM_API wefm_status wefm_face_get_options(const wefm_face* face, wefm_options* options) {
  WEFM_REQUIRE(face, "wefm_face_get_options");
  WEFM_REQUIRE(options, "wefm_face_get_options");
  return on_face(const_cast<wefm_face*>(face), Access::read, "wefm_face_get_options", [&] {
    wefm::capi::check_struct_size(options->struct_size, "wefm_options");
    wefm::capi::write_versioned(options, wefm::capi::to_c(face->face.options()));
  });
}

}
