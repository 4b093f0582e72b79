#pragma once
/**
 * @file openmesh.hpp
 * Flatten an OpenMesh triangle mesh in place, over wefm's C API (header-only; C++17).
 *
 *   #include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
 *   #include <wefm/openmesh.hpp>
 *
 *   OpenMesh::TriMesh_ArrayKernelT<> mesh;   // read or build it
 *   mesh.request_halfedge_texcoords2D();     // where the layout goes
 *   wefm_status st = wefm::openmesh::flatten(mesh, options);   // options: NULL for the defaults
 *
 * Inputs: every face of `mesh` must be a triangle; edges whose status has the feature bit
 * (`mesh.status(e).feature()`, with `mesh.request_edge_status()`) are cut as seams, so the two sides
 * of a feature edge get their own UVs (a closed or periodic face needs such a cut, or
 * `options->auto_cut`). Output: the UV of each face corner in
 * `mesh.texcoord2D(halfedge)` of the halfedge pointing to that corner (OpenMesh's convention for
 * per-corner texture coordinates), so seam sides keep distinct UVs. `report`, if given, receives the
 * solve's quality report (fill it with wefm_report_init first, as in C).
 *
 * Returns the first status other than WEFM_OK of the C calls (the mesh's texcoords untouched then,
 * except on WEFM_ERROR_NOT_CONVERGED, where the best layout reached is written, as the C API keeps
 * it); `message`, if given, receives the library's message. WEFM_ERROR_INVALID_ARGUMENT when a face
 * is not a triangle or the halfedge texcoords were not requested. The mesh's points, connectivity
 * and other properties are never changed.
 */
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "wefm/wefm.h"

namespace wefm::openmesh {

template <class Mesh>
wefm_status flatten(Mesh& mesh, const wefm_options* options = nullptr, wefm_report* report = nullptr,
                    std::string* message = nullptr) {
  auto fail = [&](wefm_status st, const std::string& why) {
    if (message) *message = why;
    return st;
  };
  if (!mesh.has_halfedge_texcoords2D())
    return fail(WEFM_ERROR_INVALID_ARGUMENT, "request_halfedge_texcoords2D() first: the layout is written there");
  std::vector<double> xyz;
  xyz.reserve(3 * mesh.n_vertices());
  for (auto v : mesh.vertices()) {
    const auto p = mesh.point(v);
    for (int k = 0; k < 3; ++k) xyz.push_back(static_cast<double>(p[k]));
  }
  // Corner k of triangle t is the vertex its k-th halfedge points to; that halfedge gets its UV.
  std::vector<int32_t> tris;
  std::vector<typename Mesh::HalfedgeHandle> corners;
  tris.reserve(3 * mesh.n_faces());
  corners.reserve(3 * mesh.n_faces());
  for (auto f : mesh.faces()) {
    int n = 0;
    for (auto h : mesh.fh_range(f)) {
      tris.push_back(static_cast<int32_t>(mesh.to_vertex_handle(h).idx()));
      corners.push_back(h);
      ++n;
    }
    if (n != 3) return fail(WEFM_ERROR_INVALID_ARGUMENT, "face " + std::to_string(f.idx()) + " has " + std::to_string(n) + " corners, not 3");
  }
  std::vector<int32_t> seams;
  if (mesh.has_edge_status())
    for (auto e : mesh.edges())
      if (mesh.status(e).feature() && !mesh.is_boundary(e)) {
        const auto h = mesh.halfedge_handle(e, 0);
        seams.push_back(static_cast<int32_t>(mesh.from_vertex_handle(h).idx()));
        seams.push_back(static_cast<int32_t>(mesh.to_vertex_handle(h).idx()));
      }

  wefm_face* raw = nullptr;
  wefm_status st = wefm_face_create(&raw);
  if (st != WEFM_OK) return fail(st, wefm_last_error());
  const std::unique_ptr<wefm_face, void (*)(wefm_face*)> face(raw, &wefm_face_release);
  auto check = [&](wefm_status s) {
    if (s != WEFM_OK && message) *message = wefm_face_last_error(face.get());
    return s;
  };
  if ((st = check(wefm_face_set_mesh(face.get(), static_cast<int64_t>(mesh.n_vertices()), xyz.data(),
                                     static_cast<int64_t>(mesh.n_faces()), tris.data()))) != WEFM_OK)
    return st;
  if (options && (st = check(wefm_face_set_options(face.get(), options))) != WEFM_OK) return st;
  if (!seams.empty() &&
      (st = check(wefm_face_add_seams(face.get(), static_cast<int64_t>(seams.size() / 2), seams.data()))) != WEFM_OK)
    return st;
  const wefm_status solved = check(wefm_face_solve(face.get()));
  if (solved != WEFM_OK && solved != WEFM_ERROR_NOT_CONVERGED) return solved;

  int64_t n = 0;
  std::vector<int32_t> uses;
  if ((st = check(wefm_face_get_triangle_uses(face.get(), nullptr, 0, &n))) != WEFM_OK) return st;
  uses.resize(static_cast<size_t>(n));
  if ((st = check(wefm_face_get_triangle_uses(face.get(), uses.data(), n, &n))) != WEFM_OK) return st;
  std::vector<double> uv;
  if ((st = check(wefm_face_get_uv(face.get(), nullptr, 0, &n))) != WEFM_OK) return st;
  uv.resize(static_cast<size_t>(n));
  if ((st = check(wefm_face_get_uv(face.get(), uv.data(), n, &n))) != WEFM_OK) return st;
  if (uses.size() != corners.size()) return fail(WEFM_ERROR_INTERNAL, "the library returned a use per corner of another mesh");
  for (size_t c = 0; c < corners.size(); ++c) {
    const size_t u = static_cast<size_t>(uses[c]);
    using Scalar = typename Mesh::TexCoord2D::value_type;  // float in OpenMesh's default traits
    mesh.set_texcoord2D(corners[c], typename Mesh::TexCoord2D(static_cast<Scalar>(uv[2 * u]), static_cast<Scalar>(uv[2 * u + 1])));
  }
  if (report && (st = check(wefm_face_get_report(face.get(), report))) != WEFM_OK) return st;
  return solved;
}

}  // namespace wefm::openmesh
