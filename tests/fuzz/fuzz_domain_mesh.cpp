// libFuzzer target: meshing a solved face's domain (wefm_face_mesh_domain) with fuzzed mesh
// options and caller edge nodes, then every wefm_domain_mesh_* call on the result. Sizes are kept
// to a few hundred elements (an element size of at least 1/10 of the face's extent, at most 2
// smoothing passes unless fuzzed) so one input runs in milliseconds; NaN, infinite, zero,
// negative and tiny sizes are still tried (refused).
// Invariants checked (abort = finding): no crash, sanitizer report or WEFM_ERROR_INTERNAL; on
// success a mesh handle whose node positions are finite, whose elements index its nodes, whose
// report counts match the arrays, and which writes as OBJ; on failure no handle.
#include <wefm/wefm.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "fuzz_faces.hpp"
#include "fuzz_files.hpp"

using wefm_fuzz::check;
using wefm_fuzz::fetch;
using wefm_fuzz::Input;
using wefm_fuzz::violated;

namespace {

// Largest extent of the face's layout and of its vertices in 3D (0 without a mesh).
double extent(wefm_face* f, Input& in, std::vector<double>& xyz_of_edge, int32_t& edge) {
  int64_t edges = 0;
  edge = -1;
  if (wefm_face_edge_count(f, &edges) != WEFM_OK || edges == 0) return 0;
  edge = static_cast<int32_t>(in.u8() % edges);
  int64_t n = 0;
  check(wefm_face_get_edge(f, edge, nullptr, 0, &n), f);
  std::vector<int32_t> chain(static_cast<size_t>(n));
  check(wefm_face_get_edge(f, edge, chain.data(), n, &n), f);
  // The edge's own vertices (as 3D points of its uses), and the extent of the UV domain.
  int64_t nu = 0;
  check(wefm_face_get_uv(f, nullptr, 0, &nu), f);
  std::vector<double> uv(static_cast<size_t>(nu));
  check(wefm_face_get_uv(f, uv.data(), nu, &nu), f);
  double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
  for (size_t i = 0; i < uv.size(); ++i) lo[i % 2] = std::fmin(lo[i % 2], uv[i]), hi[i % 2] = std::fmax(hi[i % 2], uv[i]);
  std::vector<int32_t> uses(static_cast<size_t>(nu / 2));
  int64_t k = 0;
  check(wefm_face_get_use_vertices(f, uses.data(), static_cast<int64_t>(uses.size()), &k), f);
  xyz_of_edge.clear();
  for (int32_t v : chain) {
    // The vertex's position through the mapping of one of its uses.
    for (size_t u = 0; u < uses.size(); ++u)
      if (uses[u] == v) {
        double p[3];
        check(wefm_face_map_uv_to_3d(f, 1, &uv[2 * u], p, nullptr, nullptr), f);
        xyz_of_edge.insert(xyz_of_edge.end(), {p[0], p[1], p[2]});
        break;
      }
  }
  // Sizes are in 3D units: a collapsed layout (an unconverged roll-out of an uncut tube) has a tiny
  // UV extent, and a size from it alone asks for tens of millions of elements of a valid request.
  double lo3[3] = {1e300, 1e300, 1e300}, hi3[3] = {-1e300, -1e300, -1e300};
  std::vector<double> xyz(uv.size() / 2 * 3);
  if (!uv.empty()) check(wefm_face_map_uv_to_3d(f, static_cast<int64_t>(uv.size() / 2), uv.data(), xyz.data(), nullptr, nullptr), f);
  for (size_t i = 0; i < xyz.size(); ++i) lo3[i % 3] = std::fmin(lo3[i % 3], xyz[i]), hi3[i % 3] = std::fmax(hi3[i % 3], xyz[i]);
  double span = std::fmax(hi[0] - lo[0], hi[1] - lo[1]);
  for (int k = 0; k < 3 && !xyz.empty(); ++k) span = std::fmax(span, hi3[k] - lo3[k]);
  return span;
}

// Caller nodes along an edge: its own vertices, some points between them, some moved off it.
void edge_nodes(wefm_face* f, Input& in, int32_t edge, const std::vector<double>& chain) {
  if (edge < 0 || chain.size() < 6) return;
  std::vector<double> nodes;
  const size_t nv = chain.size() / 3;
  for (size_t i = 0; i + 1 < nv; ++i) {
    const int extra = in.u8() % 4;
    for (int e = 0; e <= extra; ++e) {
      const double t = static_cast<double>(e) / (extra + 1);
      for (int k = 0; k < 3; ++k) nodes.push_back((1 - t) * chain[3 * i + static_cast<size_t>(k)] + t * chain[3 * (i + 1) + static_cast<size_t>(k)]);
    }
  }
  for (int k = 0; k < 3; ++k) nodes.push_back(chain[3 * (nv - 1) + static_cast<size_t>(k)]);
  const int mutations = in.u8() % 3;
  for (int m = 0; m < mutations; ++m) nodes[in.u8() % nodes.size()] += in.u8() % 2 ? in.number() : 1e-9;
  if (in.u8() % 8 == 0) nodes.resize(in.u8() % 2 ? 3 : 0);  // too few nodes
  const int64_t n = static_cast<int64_t>(nodes.size() / 3);
  check(wefm_face_set_edge_nodes(f, in.u8() % 16 == 0 ? in.index(-1, 8) : edge, n, nodes.empty() ? chain.data() : nodes.data()), f);
}

wefm_mesh_options mesh_options(Input& in, double span) {
  wefm_mesh_options o;
  wefm_mesh_options_init(&o);
  const uint8_t kind = in.u8() % 5;
  o.type = kind == 0 ? WEFM_MESH_TRANSFINITE : kind == 1 ? WEFM_MESH_AUTO : WEFM_MESH_FREE;
  o.smoothing_iterations = 2;
  const uint8_t how = in.u8();
  if (how % 16 == 0) {
    o.size = in.number();  // NaN, inf, 0, negative, tiny, huge: refused or one element
    if (std::isfinite(o.size) && std::fabs(o.size) < span / 10 && std::fabs(o.size) > 1e-200) o.size = span / 10;
  } else {
    o.size = span * (0.1 + (how % 64) / 32.0);
  }
  const int n = in.u8() % 6;
  for (int k = 0; k < n; ++k) {
    switch (in.u8() % 10) {
      case 0: o.corners[in.u8() % 4] = in.index(-1, 40); break;
      case 1: o.quads = in.u8() & 1; break;
      case 2: o.smoothing_iterations = in.index(-1, 4); break;
      case 3: o.corner_angle_deg = in.u8() % 8 == 0 ? in.number() : in.u8() * (180.0 / 255); break;
      case 4: o.min_angle_deg = in.u8() % 8 == 0 ? in.number() : in.u8() * (40.0 / 255); break;
      case 5: o.max_elements = in.index(-1, 400); break;
      case 6: o.type = in.index(-1, 2); break;
      case 7: o.elements = in.index(-1, 3); break;
      case 8: o.split_chords = in.index(-1, 2); break;
      default: o.struct_size = in.u8() % 2 ? 0 : sizeof(size_t) + in.u8() % 64; break;  // old/odd callers
    }
  }
  return o;
}

void inspect(wefm_domain_mesh* dm, Input& in) {
  if (wefm_domain_mesh_retain(dm) != WEFM_OK) violated("wefm_domain_mesh_retain", wefm_last_error());
  wefm_domain_mesh_release(dm);
  const auto uv = fetch<double>(nullptr, [&](double* b, int64_t c, int64_t* k) { return wefm_domain_mesh_get_uv(dm, b, c, k); }, true);
  const auto xyz = fetch<double>(nullptr, [&](double* b, int64_t c, int64_t* k) { return wefm_domain_mesh_get_xyz(dm, b, c, k); }, true);
  const auto el = fetch<int32_t>(nullptr, [&](int32_t* b, int64_t c, int64_t* k) { return wefm_domain_mesh_get_elements(dm, b, c, k); }, true);
  const int64_t nodes = static_cast<int64_t>(uv.size() / 2);
  if (static_cast<int64_t>(xyz.size()) != 3 * nodes) violated("domain mesh", "uv and xyz counts differ");
  for (double x : uv)
    if (!std::isfinite(x)) violated("domain mesh", "a non-finite UV node");
  for (double x : xyz)
    if (!std::isfinite(x)) violated("domain mesh", "a non-finite 3D node");
  wefm_mesh_report r;
  wefm_mesh_report_init(&r);
  if (in.u8() % 8 == 0) r.struct_size = in.u8() % 2 ? 0 : sizeof(size_t) + in.u8() % 64;
  const wefm_status s = wefm_domain_mesh_get_report(dm, &r);
  check(s, nullptr);
  // Four nodes per element (the report's, else as the array allows): a fourth node -1 is a triangle
  // among quads, nowhere else.
  const bool fours = s == WEFM_OK && r.struct_size == sizeof r ? r.nodes_per_element == 4 : el.size() % 4 == 0;
  int64_t quads = 0;
  for (size_t i = 0; i < el.size(); ++i) {
    if (fours && i % 4 == 3 && el[i] == -1) continue;
    if (fours && i % 4 == 3) ++quads;
    if (el[i] < 0 || el[i] >= nodes) violated("domain mesh", "an element names a node that does not exist");
  }
  if (s == WEFM_OK && r.struct_size == sizeof r) {
    if (r.nodes != nodes || (r.nodes_per_element != 3 && r.nodes_per_element != 4) || r.elements * r.nodes_per_element != static_cast<int64_t>(el.size()))
      violated("domain mesh report", "counts differ from the arrays");
    if (r.quads != (r.nodes_per_element == 4 ? quads : 0) || !(r.quad_area_fraction >= 0 && r.quad_area_fraction <= 1))
      violated("domain mesh report", "quad count or area share differs from the elements");
  }
  // Written to the process's private temporary folder (fuzz_files.hpp), removed at exit.
  check(wefm_domain_mesh_write_obj(dm, wefm_fuzz::temp_path("mesh.obj").c_str()), nullptr);
  check(wefm_domain_mesh_write_obj(dm, wefm_fuzz::temp_folder().c_str()), nullptr);  // a folder: WEFM_ERROR_IO
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  Input in(data, size);
  wefm_face* f = wefm_fuzz::solved_face(in);
  std::vector<double> chain;
  int32_t edge = -1;
  int32_t solved = 0;
  check(wefm_face_has_result(f, &solved), f);
  const double span = solved ? extent(f, in, chain, edge) : 1.0;
  for (int round = 0; round < 3 && !in.empty(); ++round) {
    const uint8_t op = in.u8() % 4;
    if (op == 0) edge_nodes(f, in, edge, chain);
    if (op == 1) check(wefm_face_clear_edge_nodes(f), f);
    const wefm_mesh_options o = mesh_options(in, span > 0 ? span : 1.0);
    wefm_domain_mesh* dm = reinterpret_cast<wefm_domain_mesh*>(&edge);  // must be reset to NULL on failure
    const wefm_status s = wefm_face_mesh_domain(f, &o, &dm);
    check(s, f);
    if ((s == WEFM_OK) != (dm != nullptr)) violated("wefm_face_mesh_domain", "handle/status mismatch");
    if (dm) {
      inspect(dm, in);
      wefm_domain_mesh_release(dm);
    }
  }
  wefm_face_release(f);
  return 0;
}
