// Triangle meshes read from files (the CLI's entry point) or made from arrays.
#include "handles.hpp"

using wefm::capi::guarded;

extern "C" {

WEFM_API wefm_status wefm_mesh_read(const char* path, double merge_tolerance, wefm_mesh** out) {
  WEFM_REQUIRE(out, "wefm_mesh_read");
  *out = nullptr;
  WEFM_REQUIRE(path, "wefm_mesh_read");
  return guarded(nullptr, [&] {
    wefm::ReadResult r = wefm::read_mesh(path, merge_tolerance);
    auto* m = new wefm_mesh;
    m->mesh = std::move(r.mesh);
    m->merged_vertices = r.merged_vertices;
    *out = m;
  });
}

WEFM_API wefm_status wefm_mesh_create(int64_t vertex_count, const double* xyz, int64_t triangle_count, const int32_t* tri, wefm_mesh** out) {
  WEFM_REQUIRE(out, "wefm_mesh_create");
  *out = nullptr;
  WEFM_REQUIRE(xyz, "wefm_mesh_create");
  WEFM_REQUIRE(tri, "wefm_mesh_create");
  return guarded(nullptr, [&] {
    if (vertex_count < 0 || triangle_count < 0 || vertex_count > 0x7fffffff || triangle_count > 0x7fffffff / 3)
      throw wefm::Error(wefm::Errc::invalid_argument, "vertex or triangle count out of range");
    auto* m = new wefm_mesh;
    m->mesh.vertices.resize(static_cast<size_t>(vertex_count));
    for (int64_t v = 0; v < vertex_count; ++v) m->mesh.vertices[static_cast<size_t>(v)] = wefm::Vec3(xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]);
    m->mesh.triangles.resize(static_cast<size_t>(triangle_count));
    for (int64_t t = 0; t < triangle_count; ++t) {
      for (int j = 0; j < 3; ++j) {
        const int32_t v = tri[3 * t + j];
        if (v < 0 || v >= vertex_count) {
          delete m;
          throw wefm::Error(wefm::Errc::out_of_range, "triangle " + std::to_string(t) + ": vertex index " + std::to_string(v) + " out of range [0, " + std::to_string(vertex_count) + ")");
        }
        m->mesh.triangles[static_cast<size_t>(t)][j] = v;
      }
    }
    *out = m;
  });
}

WEFM_API wefm_status wefm_mesh_retain(wefm_mesh* mesh) {
  WEFM_REQUIRE(mesh, "wefm_mesh_retain");
  mesh->refs.fetch_add(1);
  return WEFM_OK;
}

WEFM_API void wefm_mesh_release(wefm_mesh* mesh) {
  if (mesh && mesh->refs.fetch_sub(1) == 1) delete mesh;
}

WEFM_API wefm_status wefm_mesh_get_vertices(const wefm_mesh* mesh, double* xyz, int64_t capacity, int64_t* count) {
  WEFM_REQUIRE(mesh, "wefm_mesh_get_vertices");
  WEFM_REQUIRE(count, "wefm_mesh_get_vertices");
  return guarded(nullptr, [&] {
    const auto& vs = mesh->mesh.vertices;
    wefm::capi::copy_out_records(vs.size(), 3, xyz, capacity, count, [&](std::size_t i, double* out) {
      for (int k = 0; k < 3; ++k) out[k] = vs[i][k];
    });
  });
}

WEFM_API wefm_status wefm_mesh_get_triangles(const wefm_mesh* mesh, int32_t* tri, int64_t capacity, int64_t* count) {
  WEFM_REQUIRE(mesh, "wefm_mesh_get_triangles");
  WEFM_REQUIRE(count, "wefm_mesh_get_triangles");
  return guarded(nullptr, [&] {
    const auto& ts = mesh->mesh.triangles;
    wefm::capi::copy_out_records(ts.size(), 3, tri, capacity, count, [&](std::size_t i, int32_t* out) {
      for (int k = 0; k < 3; ++k) out[k] = static_cast<int32_t>(ts[i][k]);
    });
  });
}

WEFM_API wefm_status wefm_mesh_get_info(const wefm_mesh* mesh, wefm_mesh_info* info) {
  WEFM_REQUIRE(mesh, "wefm_mesh_get_info");
  WEFM_REQUIRE(info, "wefm_mesh_get_info");
  return guarded(nullptr, [&] {
    wefm::capi::check_struct_size(info->struct_size, "wefm_mesh_info");
    const wefm::MeshStats s = wefm::compute_stats(mesh->mesh);
    wefm_mesh_info r{};
    r.struct_size = sizeof(r);
    r.vertices = static_cast<int64_t>(mesh->mesh.vertices.size());
    r.triangles = static_cast<int64_t>(mesh->mesh.triangles.size());
    r.boundary_loops = s.boundary_loops;
    r.components = s.components;
    r.genus = s.genus;
    r.non_manifold_edges = s.non_manifold_edges;
    r.non_manifold_vertices = s.non_manifold_vertices;
    r.degenerate_triangles = s.degenerate_triangles;
    r.duplicate_triangles = s.duplicate_triangles;
    r.inconsistent_edges = s.inconsistent_edges;
    r.merged_vertices = mesh->merged_vertices;
    for (int k = 0; k < 3; ++k) {
      r.bbox_min[k] = s.bbox_min[k];
      r.bbox_max[k] = s.bbox_max[k];
    }
    r.area = s.area;
    r.mean_edge_length = s.mean_edge_length;
    wefm::capi::write_versioned(info, r);
  });
}

}
