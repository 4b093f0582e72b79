// Meshing a solved domain: caller edge nodes, the mesh handle, its arrays, report and OBJ output.
#include <cstdio>
#include <memory>
#include <string>

#include "handles.hpp"
#include "wefm/core/meshing/domain_mesh.hpp"

struct wefm_domain_mesh {
  std::atomic<int> refs{1};
  wefm::meshing::DomainMesh mesh;
};

using wefm::capi::Access;
using wefm::capi::guarded;
using wefm::capi::on_face;

namespace {

wefm::meshing::MeshOptions convert(const wefm_mesh_options& o) {
  wefm::meshing::MeshOptions m;
  m.type = static_cast<wefm::meshing::MeshType>(o.type);
  m.size = o.size;
  for (int k = 0; k < 4; ++k) m.corners[static_cast<size_t>(k)] = o.corners[k];
  m.quads = o.quads != 0;
  m.smoothing_iterations = o.smoothing_iterations;
  m.corner_angle_deg = o.corner_angle_deg;
  m.min_angle_deg = o.min_angle_deg;
  m.max_elements = o.max_elements;
  m.elements = static_cast<wefm::meshing::Elements>(o.elements);
  m.split_chords = o.split_chords != 0;
  return m;
}

wefm_mesh_options default_mesh_options() {
  wefm_mesh_options o{};
  wefm_mesh_options_init(&o, sizeof o);
  return o;
}

}  // namespace

extern "C" {

WEFM_API wefm_status wefm_face_set_edge_nodes(wefm_face* face, int32_t edge, int64_t n, const double* xyz) {
  WEFM_REQUIRE(face, "wefm_face_set_edge_nodes");
  WEFM_REQUIRE(xyz, "wefm_face_set_edge_nodes");
  return on_face(face, Access::change, "wefm_face_set_edge_nodes", [&] {
    if (n < 2) throw wefm::Error(wefm::Errc::invalid_argument, "edge nodes must include both end vertices (n = " + std::to_string(n) + ")");
    std::vector<wefm::Vec3> nodes(static_cast<size_t>(n));
    for (int64_t i = 0; i < n; ++i) nodes[static_cast<size_t>(i)] = wefm::Vec3(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
    face->face.set_edge_nodes(edge, std::move(nodes));
  });
}

WEFM_API wefm_status wefm_face_clear_edge_nodes(wefm_face* face) {
  WEFM_REQUIRE(face, "wefm_face_clear_edge_nodes");
  return on_face(face, Access::change, "wefm_face_clear_edge_nodes", [&] { face->face.clear_edge_nodes(); });
}

WEFM_API wefm_status wefm_face_mesh_domain(wefm_face* face, const wefm_mesh_options* options, wefm_domain_mesh** out) {
  WEFM_REQUIRE(face, "wefm_face_mesh_domain");
  WEFM_REQUIRE(options, "wefm_face_mesh_domain");
  WEFM_REQUIRE(out, "wefm_face_mesh_domain");
  *out = nullptr;
  const wefm_status status = on_face(face, Access::change, "wefm_face_mesh_domain", [&] {
    face->cancel.store(false);
    wefm::capi::check_struct_size(options->struct_size, "wefm_mesh_options");
    const wefm_mesh_options o = wefm::capi::read_versioned(options, default_mesh_options());
    const wefm::FlattenResult& r = face->face.result();
    auto dm = std::make_unique<wefm_domain_mesh>();
    wefm::meshing::MeshControl control;
    control.cancel = &face->cancel;
    if (const wefm::ProgressFn progress = wefm::capi::progress_of(face))
      control.progress = [progress](double f) { return progress(f, "mesh"); };
    const wefm::capi::BusyFace busy(face);
    dm->mesh = wefm::meshing::mesh_domain(face->face.mesh(), face->face.topology(), r.uv, convert(o), face->face.edge_nodes(), control);
    *out = dm.release();
  });
  wefm::capi::free_if_released(face);
  return status;
}

WEFM_API wefm_status wefm_domain_mesh_retain(wefm_domain_mesh* mesh) {
  WEFM_REQUIRE(mesh, "wefm_domain_mesh_retain");
  mesh->refs.fetch_add(1);
  return WEFM_OK;
}

WEFM_API void wefm_domain_mesh_release(wefm_domain_mesh* mesh) {
  if (mesh && mesh->refs.fetch_sub(1) == 1) delete mesh;
}

WEFM_API wefm_status wefm_domain_mesh_get_uv(const wefm_domain_mesh* mesh, double* uv, int64_t capacity, int64_t* count) {
  WEFM_REQUIRE(mesh, "wefm_domain_mesh_get_uv");
  WEFM_REQUIRE(count, "wefm_domain_mesh_get_uv");
  return guarded(nullptr, [&] {
    const auto& ps = mesh->mesh.uv;
    wefm::capi::copy_out_records(ps.size(), 2, uv, capacity, count, [&](std::size_t i, double* out) {
      out[0] = ps[i].x();
      out[1] = ps[i].y();
    });
  });
}

WEFM_API wefm_status wefm_domain_mesh_get_xyz(const wefm_domain_mesh* mesh, double* xyz, int64_t capacity, int64_t* count) {
  WEFM_REQUIRE(mesh, "wefm_domain_mesh_get_xyz");
  WEFM_REQUIRE(count, "wefm_domain_mesh_get_xyz");
  return guarded(nullptr, [&] {
    const auto& ps = mesh->mesh.xyz;
    wefm::capi::copy_out_records(ps.size(), 3, xyz, capacity, count, [&](std::size_t i, double* out) {
      out[0] = ps[i].x();
      out[1] = ps[i].y();
      out[2] = ps[i].z();
    });
  });
}

WEFM_API wefm_status wefm_domain_mesh_get_elements(const wefm_domain_mesh* mesh, int32_t* nodes, int64_t capacity, int64_t* count) {
  WEFM_REQUIRE(mesh, "wefm_domain_mesh_get_elements");
  WEFM_REQUIRE(count, "wefm_domain_mesh_get_elements");
  return guarded(nullptr, [&] { wefm::capi::copy_out(mesh->mesh.elements, nodes, capacity, count); });
}

WEFM_API wefm_status wefm_domain_mesh_get_report(const wefm_domain_mesh* mesh, wefm_mesh_report* report) {
  WEFM_REQUIRE(mesh, "wefm_domain_mesh_get_report");
  WEFM_REQUIRE(report, "wefm_domain_mesh_get_report");
  return guarded(nullptr, [&] {
    wefm::capi::check_struct_size(report->struct_size, "wefm_mesh_report");
    const wefm::meshing::MeshReport& s = mesh->mesh.report;
    wefm_mesh_report r{};
    r.struct_size = sizeof(r);
    r.nodes = s.nodes;
    r.elements = s.elements;
    r.nodes_per_element = s.nodes_per_element;
    r.lambda_mesh = s.lambda_mesh;
    r.lambda_min = s.lambda_min;
    r.fraction_below_0_6 = s.fraction_below_0_6;
    r.scaled_jacobian_min = s.scaled_jacobian_min;
    r.scaled_jacobian_mean = s.scaled_jacobian_mean;
    r.wiggle_max = s.wiggle_max;
    r.wiggle_mean = s.wiggle_mean;
    r.time_boundary = s.time_boundary;
    r.time_mesh = s.time_mesh;
    r.time_smooth = s.time_smooth;
    r.time_map = s.time_map;
    r.quads = s.quads;
    r.quad_area_fraction = s.quad_area_fraction;
    r.transfinite = s.transfinite ? 1 : 0;
    r.automatic_fallback = static_cast<int32_t>(s.automatic_fallback);
    r.refused_grid_scaled_jacobian_min = s.refused_grid_scaled_jacobian_min;
    wefm::capi::write_versioned(report, r);
  });
}

WEFM_API wefm_status wefm_domain_mesh_write_obj(const wefm_domain_mesh* mesh, const char* path) {
  WEFM_REQUIRE(mesh, "wefm_domain_mesh_write_obj");
  WEFM_REQUIRE(path, "wefm_domain_mesh_write_obj");
  return guarded(nullptr, [&] { wefm::meshing::write_obj(path, mesh->mesh); });
}

}
