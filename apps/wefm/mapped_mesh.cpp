#include "mapped_mesh.hpp"

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "names.hpp"
#include "owned.hpp"
#include "size_query.hpp"

namespace wefm_cli {

namespace {

// The outer loop's uses of the corner vertices, in loop order, into options.corners, where there are
// exactly four (a corner vertex used twice by the loop, on a seam, is a corner both times on a
// cylinder between two circles); else the library detects them.
void set_corner_uses(wefm_face* face, const std::array<int32_t, 4>& corner_vertices, wefm_mesh_options& options) {
  if (corner_vertices[0] < 0) return;
  int32_t loop = 0;
  std::vector<int32_t> uses, vertex_of;
  if (wefm_face_outer_loop(face, &loop) != WEFM_OK ||
      fetch(uses, [&](int32_t* b, int64_t c, int64_t* n) { return wefm_face_get_loop_uses(face, loop, b, c, n); }) != WEFM_OK ||
      fetch(vertex_of, [&](int32_t* b, int64_t c, int64_t* n) { return wefm_face_get_use_vertices(face, b, c, n); }) != WEFM_OK)
    return;
  std::vector<int32_t> found;
  for (int32_t u : uses)
    if (u >= 0 && static_cast<size_t>(u) < vertex_of.size() &&
        std::find(corner_vertices.begin(), corner_vertices.end(), vertex_of[static_cast<size_t>(u)]) != corner_vertices.end())
      found.push_back(u);
  if (found.size() == 4) std::copy(found.begin(), found.end(), options.corners);
}

// Why WEFM_MESH_AUTO made its free mesh, from the report.
std::string fallback_reason(const wefm_mesh_report& r) {
  const char* why = automatic_fallback_name(r.automatic_fallback);
  if (!why) return "the library made a free mesh";
  std::string text = std::string("the library's automatic type: ") + why;
  if (r.automatic_fallback == WEFM_FALLBACK_POOR_GRID) {
    char detail[96];
    std::snprintf(detail, sizeof detail, " (its worst quad's scaled Jacobian %.3f, below 0.3)", r.refused_grid_scaled_jacobian_min);
    text += detail;
  } else if (r.automatic_fallback == WEFM_FALLBACK_GRID_REFUSED) {
    text += " (opposite sides with unlike node counts, or over max_elements)";
  }
  return text;
}

}  // namespace

MappedOutcome mesh_mapped(wefm_face* face, const MappedRequest& request, const wefm_mesh_options& free_options, wefm_domain_mesh** out) {
  MappedOutcome outcome;
  wefm_mesh_options map_options = request.options;
  set_corner_uses(face, request.corner_vertices, map_options);
  wefm_domain_mesh* grid_raw = nullptr;
  outcome.status = wefm_face_mesh_domain(face, &map_options, &grid_raw);
  OwnedDomainMesh grid(grid_raw);
  if (outcome.status != WEFM_OK && outcome.status != WEFM_ERROR_UNSUPPORTED) return outcome;
  wefm_mesh_report g;
  wefm_mesh_report_init(&g, sizeof g);
  char text[160] = "";
  if (outcome.status == WEFM_ERROR_UNSUPPORTED) {
    outcome.refused = wefm_face_last_error(face);
  } else if (wefm_domain_mesh_get_report(grid.get(), &g) != WEFM_OK) {
    outcome.refused = "no report of the grid";
  } else if (!g.transfinite) {  // WEFM_MESH_AUTO's own free mesh
    outcome.refused = fallback_reason(g);
    *out = grid.release();
    return outcome;
  } else if (!(request.most_elements > 0)) {
    outcome.transfinite = true;
    *out = grid.release();
    return outcome;
  }
  wefm_domain_mesh* free_raw = nullptr;
  const wefm_status fs = wefm_face_mesh_domain(face, &free_options, &free_raw);
  OwnedDomainMesh free_mesh(free_raw);
  wefm_mesh_report f;
  wefm_mesh_report_init(&f, sizeof f);
  if (outcome.refused.empty()) {
    // The grid is good; it is kept unless the free mesh is much leaner (or fails).
    if (fs != WEFM_OK || wefm_domain_mesh_get_report(free_mesh.get(), &f) != WEFM_OK ||
        !(static_cast<double>(g.elements) > request.most_elements * static_cast<double>(f.elements))) {
      outcome.status = WEFM_OK;
      outcome.transfinite = true;
      *out = grid.release();
      return outcome;
    }
    std::snprintf(text, sizeof text, "the grid has %lld elements, more than %g times the free mesh's %lld",
                  static_cast<long long>(g.elements), request.most_elements, static_cast<long long>(f.elements));
    outcome.refused = text;
  }
  outcome.status = fs;
  *out = free_mesh.release();
  return outcome;
}

}  // namespace wefm_cli
