#include "wefm/core/meshing/free_mesh.hpp"

#include <chrono>
#include <algorithm>
#include <cmath>

#include "wefm/core/error.hpp"
#include "wefm/core/meshing/smoothing.hpp"
#include "wefm/core/meshing/triangulation.hpp"

namespace wefm::meshing {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Circumradius of the 3D triangle through three nodes.
double circumradius(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double la = (b - c).norm(), lb = (c - a).norm(), lc = (a - b).norm();
  const double area2 = (b - a).cross(c - a).norm();
  return area2 > 0 ? la * lb * lc / (2 * area2) : 1e300;
}

}  // namespace

void free_mesh(const std::vector<LoopNodes>& loops, const SurfaceMap& map, const MeshOptions& o, DomainMesh& out,
               const std::atomic<bool>* cancel) {
  auto check_cancel = [&] {
    if (cancel && cancel->load()) fail(Errc::cancelled, "meshing cancelled");
  };
  auto t0 = std::chrono::steady_clock::now();
  std::vector<P2> pts;
  std::vector<std::array<Index, 2>> segs;
  for (const LoopNodes& l : loops) {
    const Index base = static_cast<Index>(pts.size()), n = static_cast<Index>(l.uv.size());
    for (Index k = 0; k < n; ++k) {
      pts.push_back(l.uv[static_cast<size_t>(k)]);
      out.xyz.push_back(l.xyz[static_cast<size_t>(k)]);
      segs.push_back({base + k, base + (k + 1) % n});
    }
  }
  out.boundary_nodes = static_cast<Index>(pts.size());
  Triangulation tr(pts, segs);
  // Size in 3D, measured on the mapped nodes: the UV size is then h times the local UV/3D scale
  // without estimating that scale. An equilateral triangle of side h has circumradius h / sqrt(3);
  // the 1.25 margin keeps triangles standing on boundary segments of length ~h (which are never
  // split) from triggering a cascade of tiny elements, and gives a mean edge length near h.
  const double rmax = 1.25 * o.size / std::sqrt(3.0);
  auto size_class = [&](Index a, Index b, Index c) {
    const Vec3 &A = out.xyz[static_cast<size_t>(a)], &B = out.xyz[static_cast<size_t>(b)], &C = out.xyz[static_cast<size_t>(c)];
    if (circumradius(A, B, C) > rmax) return 1;
    // Elements far below h are left to smoothing rather than split for their angles.
    return std::min({(A - B).norm(), (B - C).norm(), (C - A).norm()}) < 0.3 * o.size ? -1 : 0;
  };
  std::int64_t inserted = 0;
  auto on_insert = [&](Index v) {
    // Throwing here leaves the triangulation consistent; it is discarded with the exception.
    if ((++inserted & 255) == 0) check_cancel();
    Vec3 x;
    map.lift(tr.node(v), x);
    if (out.xyz.size() <= static_cast<size_t>(v)) out.xyz.resize(static_cast<size_t>(v) + 1);
    out.xyz[static_cast<size_t>(v)] = x;
  };
  // A triangulation has about twice as many triangles as nodes: stop refining near the cap.
  const std::int64_t max_nodes = o.max_elements > 0 ? o.max_elements / 2 + 1 : 0;
  tr.refine(size_class, o.min_angle_deg * kPi / 180.0, max_nodes, on_insert);
  out.uv.resize(static_cast<size_t>(tr.node_count()));
  for (Index v = 0; v < tr.node_count(); ++v) out.uv[static_cast<size_t>(v)] = tr.node(v);
  auto tris = tr.triangles();
  out.report.time_mesh = seconds_since(t0);

  check_cancel();
  t0 = std::chrono::steady_clock::now();
  improve_in_3d(out.uv, out.xyz, tris, out.boundary_nodes, o.smoothing_iterations, map);
  out.report.time_smooth = seconds_since(t0);
  out.nodes_per_element = 3;
  for (const auto& t : tris) out.elements.insert(out.elements.end(), t.begin(), t.end());
}

}  // namespace wefm::meshing
