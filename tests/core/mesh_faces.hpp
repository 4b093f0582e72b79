#pragma once
// Solved faces for the meshing tests: a face, its topology and its domain, built from the
// generators of meshes.hpp.
#include <map>
#include <memory>
#include <utility>

#include "solve_helpers.hpp"
#include "wefm/common/element_corners.hpp"
#include "wefm/core/meshing/domain_mesh.hpp"
#include "wefm/core/meshing/surface_locator.hpp"

namespace wefm::test {

struct SolvedFace {
  std::unique_ptr<Face> face = std::make_unique<Face>();
  const TriMesh& mesh() const { return face->mesh(); }
  const Topology& topo() const { return face->topology(); }  // built by solve: no rebuild here
  const VectorXc& uv() const { return face->result().uv; }
  meshing::DomainMesh mesh_domain(const meshing::MeshOptions& o, const meshing::EdgeNodes& given = {}) const {
    return meshing::mesh_domain(mesh(), topo(), uv(), o, given);
  }
};

inline SolvedFace solved(const TriMesh& m, double s = 0.0, const std::vector<std::pair<Index, Index>>& seams = {},
                         EdgeMode mode = EdgeMode::Auto) {
  SolvedFace f;
  f.face->set_mesh(m);
  Options o = with_s(s);
  o.default_edge_mode = mode;
  f.face->set_options(o);
  if (!seams.empty()) f.face->add_seams(seams);
  f.face->solve(nullptr, nullptr);
  return f;
}

inline TriMesh unit_square(int n) {
  return grid(n, n, [](double u, double v) { return Vec3(u, v, 0.0); });
}

// Every edge of a domain mesh (triangles, quads, or quads with triangles ending in -1): how many
// elements use it, each way round counted apart.
inline std::map<std::pair<Index, Index>, int> directed_edges(const meshing::DomainMesh& dm) {
  std::map<std::pair<Index, Index>, int> out;
  const size_t npe = static_cast<size_t>(dm.nodes_per_element);
  for (size_t e = 0; e < dm.elements.size() / npe; ++e)
    for (size_t k = 0, n = wefm_common::element_corners(&dm.elements[npe * e], dm.nodes_per_element); k < n; ++k)
      out[{dm.elements[npe * e + k], dm.elements[npe * e + (k + 1) % n]}]++;
  return out;
}

// Largest distance from a mesh node to the 3D triangulation, relative to its bounding box.
inline double max_off_surface(const TriMesh& m, const meshing::DomainMesh& dm) {
  const meshing::SurfaceLocator loc(m);
  double worst = 0;
  for (const Vec3& x : dm.xyz) worst = std::max(worst, loc.closest(x).distance);
  return worst / loc.bbox_diagonal();
}

}  // namespace wefm::test
