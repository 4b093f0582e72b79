#include "wefm/core/meshing/domain_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "wefm/core/sys/clock.hpp"
#include "wefm/core/sys/error.hpp"
#include "wefm/core/meshing/free_mesh.hpp"
#include "wefm/core/meshing/mesh_quality.hpp"
#include "wefm/core/meshing/recombine.hpp"
#include "wefm/core/meshing/size_field.hpp"
#include "wefm/core/meshing/transfinite.hpp"
#include "wefm/core/method/quality.hpp"

namespace wefm::meshing {

namespace {

// The worst quad a recombination makes (3D scaled Jacobian): a quad with a corner near 17 degrees
// or 163 is worse for a solver than the two triangles it replaces.
constexpr double kMinQuadQuality = 0.3;

// The free mesh (METHOD §9.2): the boundary discretised, triangulated and refined in UV, lifted to
// 3D, then paired into quads and split as the options ask.
void mesh_free(const TriMesh& mesh, const Topology& topo, const VectorXc& uv, const SurfaceMap& map, const MeshOptions& o,
               const EdgeNodes& given, double estimate, const MeshControl& control, DomainMesh& out) {
  double t0 = now();
  const auto loops = discretise_loops(mesh, topo, uv, o.size, o.corner_angle_deg * kPi / 180.0, given, kSizeGradation);
  out.report.time_boundary = now() - t0;
  control.check(0.1);
  free_mesh(loops, map, o, estimate / 2.5, out, control);
  control.check(0.95);
  t0 = now();
  out.normal.resize(out.uv.size());
  for (size_t k = 0; k < out.uv.size(); ++k) {
    Vec3 x;
    if (!map.lift(out.uv[k], x, &out.normal[k])) out.report.outside_nodes++;
    if (static_cast<Index>(k) >= out.boundary_nodes) out.xyz[k] = x;
  }
  out.report.time_map = now() - t0;
  if (o.max_elements > 0 && static_cast<std::int64_t>(out.elements.size() / 3) > o.max_elements)
    fail(Errc::invalid_argument, "the free mesh needs more than max_elements = " + std::to_string(o.max_elements) + " triangles at size " + std::to_string(o.size));
  if (o.elements == Elements::Triangles) return;
  recombine(out, kMinQuadQuality);
  // All-quad meshes too: the quads split from smoothed quads start nearer their final shapes.
  smooth_quads(out, map, o.smoothing_iterations, o.elements == Elements::QuadDominant);
  if (o.elements != Elements::Quads) return;
  if (o.max_elements > 0 && static_cast<std::int64_t>(split_count(out)) > o.max_elements)
    fail(Errc::invalid_argument, "the all-quad mesh needs more than max_elements = " + std::to_string(o.max_elements) + " quads at size " + std::to_string(o.size));
  split_and_smooth(out, map, o.smoothing_iterations, kMinQuadQuality);
}

// A transfinite grid whose worst quad is below this is not chosen by MeshType::Automatic: its free
// mesh is better for a solver.
constexpr double kAutomaticGridFloor = 0.3;

// MeshType::Automatic: the transfinite grid on the caller's corners, or else on the domain's four
// corners where it has them, where the grid is good (kAutomaticGridFloor); else the free mesh, with
// the reason in the report. A grid the transfinite mesher refuses (a face with holes, opposite sides
// with unlike counts of caller nodes, more elements than max_elements) is not an error here: the free
// mesh has its own say. Corners that are not four distinct uses of the outer loop are an error, as
// for a transfinite mesh.
void mesh_automatic(const TriMesh& mesh, const Topology& topo, const VectorXc& uv, const SurfaceMap& map, const MeshOptions& o,
                    const EdgeNodes& given, double estimate, const MeshControl& control, DomainMesh& out) {
  MeshOptions grid = o;
  grid.type = MeshType::Transfinite;
  bool four_sided = false;
  if (std::any_of(o.corners.begin(), o.corners.end(), [](Index c) { return c >= 0; })) {
    try {
      transfinite_corners(topo, uv, o.corners);
      four_sided = true;
    } catch (const Error& e) {
      if (e.code() != Errc::unsupported) throw;
    }
  } else if (const auto c = four_corners(topo, uv)) {
    for (size_t k = 0; k < 4; ++k) grid.corners[k] = topo.loop_uses[static_cast<size_t>(topo.outer_loop)][(*c)[k]];
    four_sided = true;
  }
  AutomaticFallback why = AutomaticFallback::NotFourSided;
  double grid_worst = 0;
  if (four_sided) {
    try {
      DomainMesh trial;
      transfinite_mesh(mesh, topo, uv, map, grid, given, trial);
      measure_quality(trial);
      if (trial.report.quads == 0 || trial.report.scaled_jacobian_min >= kAutomaticGridFloor) {
        out = std::move(trial);
        return;
      }
      why = AutomaticFallback::PoorGrid;
      grid_worst = trial.report.scaled_jacobian_min;
    } catch (const Error& e) {
      if (e.code() != Errc::unsupported && e.code() != Errc::invalid_argument) throw;
      why = AutomaticFallback::GridRefused;
    }
  }
  mesh_free(mesh, topo, uv, map, o, given, estimate, control, out);
  measure_quality(out);
  out.report.automatic_fallback = why;
  out.report.refused_grid_scaled_jacobian_min = grid_worst;
}

}  // namespace

DomainMesh mesh_domain(const TriMesh& mesh, const Topology& topo, const VectorXc& uv, const MeshOptions& o, const EdgeNodes& given,
                       const MeshControl& control) {
  if (!(o.size > 0) || !std::isfinite(o.size)) fail(Errc::invalid_argument, "mesh size must be a positive number (got " + std::to_string(o.size) + ")");
  if (o.type != MeshType::Free && o.type != MeshType::Transfinite && o.type != MeshType::Automatic)
    fail(Errc::invalid_argument, "unknown mesh type " + std::to_string(static_cast<int>(o.type)) + " (0 free, 1 transfinite, 2 automatic)");
  if (o.elements != Elements::Triangles && o.elements != Elements::QuadDominant && o.elements != Elements::Quads)
    fail(Errc::invalid_argument, "unknown element kind " + std::to_string(static_cast<int>(o.elements)) + " (0 triangles, 1 quad-dominant, 2 quads)");
  if (!(o.min_angle_deg >= 0 && o.min_angle_deg <= 34)) fail(Errc::invalid_argument, "min_angle_deg must lie in [0, 34] for refinement to terminate (got " + std::to_string(o.min_angle_deg) + ")");
  if (o.smoothing_iterations < 0) fail(Errc::invalid_argument, "smoothing_iterations must be >= 0");
  if (o.max_elements < 0) fail(Errc::invalid_argument, "max_elements must be >= 0");
  if (uv.size() != topo.use_count) fail(Errc::invalid_state, "the face has no solved domain to mesh");
  // Guard against sizes that would mean billions of elements before doing any work.
  double area = 0;
  for (size_t t = 0; t < mesh.triangles.size(); ++t) area += triangle_area(mesh, static_cast<Index>(t));
  const double estimate = 2.5 * area / (0.433 * o.size * o.size);
  // As a number, not an integer: a tiny size makes the estimate infinite.
  if (estimate > 2e8) fail(Errc::invalid_argument, "mesh size " + message_number(o.size) + " would give about " + message_number(estimate) + " elements");

  // A self-intersecting domain boundary maps some UV points to two places: no mesh of it is valid.
  if (const std::int64_t crossings = count_boundary_intersections(topo, uv); crossings > 0)
    fail(Errc::invalid_state, "the domain's boundary intersects itself (" + std::to_string(crossings) +
                                  " crossings): solve with other options or seams before meshing");

  control.check(0.0);
  DomainMesh out;
  const SurfaceMap map(mesh, topo, uv);
  // Each way ends measured (Automatic measures the grid to judge it).
  if (o.type == MeshType::Automatic) {
    mesh_automatic(mesh, topo, uv, map, o, given, estimate, control, out);
  } else {
    if (o.type == MeshType::Transfinite) transfinite_mesh(mesh, topo, uv, map, o, given, out);
    else mesh_free(mesh, topo, uv, map, o, given, estimate, control, out);
    measure_quality(out);
  }
  // A node the mapping could not place (NaN from the mesher) would reach the caller as garbage.
  for (size_t k = 0; k < out.uv.size(); ++k)
    if (!out.uv[k].allFinite() || !out.xyz[k].allFinite())
      fail(Errc::internal, "domain mesh node " + std::to_string(k) + " has a non-finite position (UV " + message_number(out.uv[k].x()) + ", " +
                               message_number(out.uv[k].y()) + ")");
  control.check(1.0);
  return out;
}

}  // namespace wefm::meshing
