// wefm/openmesh.hpp: an OpenMesh cylinder with a feature edge along a generator is flattened in
// place; the UVs land on the halfedges, the seam's two sides apart, and the layout is the C API's.
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "wefm/openmesh.hpp"

namespace {

using Mesh = OpenMesh::TriMesh_ArrayKernelT<>;
int failures = 0;

void check(bool ok, const std::string& what) {
  if (!ok) {
    std::fprintf(stderr, "FAIL: %s\n", what.c_str());
    ++failures;
  }
}

// A closed cylinder band: `rings` rings of `sectors` vertices; returns the generator at angle 0.
std::vector<Mesh::VertexHandle> cylinder(Mesh& m, int rings, int sectors) {
  std::vector<Mesh::VertexHandle> v;
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < sectors; ++j) {
      const double a = 2 * 3.14159265358979323846 * j / sectors;
      v.push_back(m.add_vertex(Mesh::Point(static_cast<float>(std::cos(a)), static_cast<float>(std::sin(a)), static_cast<float>(0.5 * i))));
    }
  for (int i = 0; i + 1 < rings; ++i)
    for (int j = 0; j < sectors; ++j) {
      const int jn = (j + 1) % sectors;
      const auto a = v[static_cast<size_t>(i * sectors + j)], b = v[static_cast<size_t>(i * sectors + jn)];
      const auto c = v[static_cast<size_t>((i + 1) * sectors + jn)], d = v[static_cast<size_t>((i + 1) * sectors + j)];
      m.add_face(a, b, c);
      m.add_face(a, c, d);
    }
  std::vector<Mesh::VertexHandle> generator;
  for (int i = 0; i < rings; ++i) generator.push_back(v[static_cast<size_t>(i * sectors)]);
  return generator;
}

}  // namespace

int main() {
  Mesh m;
  const auto gen = cylinder(m, 4, 12);
  m.request_edge_status();
  int seam_edges = 0;
  for (size_t i = 0; i + 1 < gen.size(); ++i) {
    const auto h = m.find_halfedge(gen[i], gen[i + 1]);
    check(h.is_valid(), "generator edge exists");
    m.status(m.edge_handle(h)).set_feature(true);
    ++seam_edges;
  }
  const auto points_before = m.n_vertices();

  // Without texcoords there is nowhere to write: refused, nothing else happens.
  std::string message;
  check(wefm::openmesh::flatten(m, nullptr, nullptr, &message) == WEFM_ERROR_INVALID_ARGUMENT, "refused without texcoords");
  check(message.find("request_halfedge_texcoords2D") != std::string::npos, "message names the request: " + message);

  m.request_halfedge_texcoords2D();
  wefm_report report;
  wefm_report_init(&report, sizeof report);
  const wefm_status st = wefm::openmesh::flatten(m, nullptr, &report, &message);
  check(st == WEFM_OK, "flatten: " + std::string(wefm_status_string(st)) + " " + message);
  check(report.flipped_triangles == 0 && report.angle_distortion_max < 1 + 1e-6, "a developable cylinder unrolls exactly");
  check(m.n_vertices() == points_before, "the mesh's vertices are not changed");

  // Each face's corners: UV distances equal 3D distances (the band is developable).
  double worst = 0;
  for (auto f : m.faces()) {
    std::vector<Mesh::HalfedgeHandle> hs(m.fh_begin(f), m.fh_end(f));
    for (size_t k = 0; k < 3; ++k) {
      const auto a = hs[k], b = hs[(k + 1) % 3];
      const double d3 = (m.point(m.to_vertex_handle(a)) - m.point(m.to_vertex_handle(b))).norm();
      const double d2 = (m.texcoord2D(a) - m.texcoord2D(b)).norm();
      worst = std::max(worst, std::abs(d2 - d3) / d3);
    }
  }
  check(worst < 1e-5, "corner UV distances equal 3D distances (float texcoords), worst " + std::to_string(worst));

  // The seam's vertices carry two UVs: the corners on either side of a generator vertex differ by
  // the unrolled circumference.
  const auto v = gen[1];
  double spread = 0;
  for (auto h : m.vih_range(v))
    for (auto g : m.vih_range(v))
      if (!m.is_boundary(h) && !m.is_boundary(g)) spread = std::max(spread, static_cast<double>((m.texcoord2D(h) - m.texcoord2D(g)).norm()));
  check(spread > 5.0, "the seam's sides are apart by about 2 pi, got " + std::to_string(spread));

  // A quad face is refused by name.
  OpenMesh::PolyMesh_ArrayKernelT<> quad;
  std::vector<OpenMesh::PolyMesh_ArrayKernelT<>::VertexHandle> q;
  for (int k = 0; k < 4; ++k) q.push_back(quad.add_vertex({static_cast<float>(k & 1), static_cast<float>(k >> 1), 0.f}));
  quad.add_face(q[0], q[1], q[3], q[2]);
  quad.request_halfedge_texcoords2D();
  check(wefm::openmesh::flatten(quad, nullptr, nullptr, &message) == WEFM_ERROR_INVALID_ARGUMENT &&
            message.find("4 corners") != std::string::npos,
        "a quad is refused: " + message);

  std::printf("openmesh adapter: %d seam edges, worst edge-length error %.2e, seam spread %.3f, %d failure(s)\n", seam_edges, worst, spread,
              failures);
  return failures ? 1 : 0;
}
