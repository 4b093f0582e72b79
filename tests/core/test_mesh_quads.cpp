// Quad-dominant and all-quad free meshes (METHOD §9.5): triangles paired into quads judged in 3D,
// then, for all-quad, every element split at its edge midpoints and centre.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "mesh_faces.hpp"
#include "wefm/core/meshing/mesh_quality.hpp"
#include "wefm/core/meshing/recombine.hpp"
#include "wefm/core/meshing/surface_map.hpp"

using namespace wefm;

namespace {

// Corners of element e: 3 for a quad-dominant mesh's triangle (fourth node -1), else 4.
size_t corners(const meshing::DomainMesh& dm, size_t e) { return wefm_common::element_corners(&dm.elements[4 * e], 4); }

double area3(const meshing::DomainMesh& dm, size_t e) {
  auto X = [&](size_t k) { return dm.xyz[static_cast<size_t>(dm.elements[4 * e + k])]; };
  double a = 0.5 * (X(1) - X(0)).cross(X(2) - X(0)).norm();
  if (corners(dm, e) == 4) a += 0.5 * (X(2) - X(0)).cross(X(3) - X(0)).norm();
  return a;
}

double signed_area_uv(const meshing::DomainMesh& dm, size_t e) {
  double a = 0;
  const size_t n = corners(dm, e);
  for (size_t k = 0; k < n; ++k) {
    const meshing::P2& p = dm.uv[static_cast<size_t>(dm.elements[4 * e + k])];
    const meshing::P2& q = dm.uv[static_cast<size_t>(dm.elements[4 * e + (k + 1) % n])];
    a += p.x() * q.y() - p.y() * q.x();
  }
  return 0.5 * a;
}

// Conforming and oriented: each directed edge used once, and an edge used one way round only on the
// boundary (nodes 0..boundary_nodes-1).
void check_conforming(const meshing::DomainMesh& dm) {
  const auto edges = test::directed_edges(dm);
  int boundary = 0;
  for (const auto& [e, n] : edges) {
    CAPTURE(e.first);
    CAPTURE(e.second);
    REQUIRE(n == 1);
    if (!edges.count({e.second, e.first})) {
      ++boundary;
      CHECK(e.first < dm.boundary_nodes);
      CHECK(e.second < dm.boundary_nodes);
    }
  }
  CHECK(boundary > 0);
}

double face_area(const test::SolvedFace& f) {
  double a = 0;
  for (size_t t = 0; t < f.mesh().triangles.size(); ++t) a += triangle_area(f.mesh(), static_cast<Index>(t));
  return a;
}

}  // namespace

TEST_CASE("quad-dominant: a disk with holes is nearly all quads, each convex in UV and good in 3D, the mesh conforming") {
  const auto f = test::solved(test::disk_with_holes());
  meshing::MeshOptions o;
  o.size = 0.06;
  const auto tri = f.mesh_domain(o);
  o.elements = meshing::Elements::QuadDominant;
  const auto dm = f.mesh_domain(o);
  MESSAGE("disk with holes: ", dm.report.quads, " quads of ", dm.report.elements, " elements, area in quads ", dm.report.quad_area_fraction,
          ", scaled Jacobian min ", dm.report.scaled_jacobian_min, " mean ", dm.report.scaled_jacobian_mean);
  REQUIRE(dm.nodes_per_element == 4);
  // The same nodes as the triangle mesh: pairing moves none.
  CHECK(dm.xyz.size() == tri.xyz.size());
  CHECK(dm.report.elements == static_cast<std::int64_t>(dm.elements.size() / 4));
  CHECK(2 * dm.report.quads + (dm.report.elements - dm.report.quads) == tri.report.elements);
  CHECK(dm.report.quad_area_fraction >= 0.95);
  CHECK(dm.report.scaled_jacobian_min >= 0.3);
  // Quads paired from near-equilateral triangles are 60-120 degree rhombi: the Laplacian passes
  // alone left a mean of 0.878 here, the passes for the mean (raise_mean) 0.893.
  CHECK(dm.report.scaled_jacobian_mean >= 0.885);
  double area = 0;
  for (size_t e = 0; e < dm.elements.size() / 4; ++e) {
    CHECK(signed_area_uv(dm, e) > 0);
    area += area3(dm, e);
  }
  CHECK(area == doctest::Approx(face_area(f)).epsilon(1e-9));
  check_conforming(dm);
}

TEST_CASE("all-quad: every element a quad, the boundary's midpoints on the boundary, the mesh conforming") {
  const auto f = test::solved(test::saddle(24), 1.0);
  meshing::MeshOptions o;
  o.size = 0.1;
  o.elements = meshing::Elements::Quads;
  const auto dm = f.mesh_domain(o);
  MESSAGE("saddle, all quads: ", dm.report.elements, " quads, scaled Jacobian min ", dm.report.scaled_jacobian_min, " mean ",
          dm.report.scaled_jacobian_mean);
  REQUIRE(dm.nodes_per_element == 4);
  CHECK(dm.report.quads == dm.report.elements);
  CHECK(dm.report.quad_area_fraction == 1.0);
  // Split from the quad-dominant mesh at the size asked for: the quads' sides are about half of it,
  // as Gmsh's subdivision into quads gives.
  double sides = 0;
  for (size_t e = 0; e < dm.elements.size(); e += 4)
    for (size_t k = 0; k < 4; ++k) sides += (dm.xyz[static_cast<size_t>(dm.elements[e + k])] - dm.xyz[static_cast<size_t>(dm.elements[e + (k + 1) % 4])]).norm();
  CHECK(sides / static_cast<double>(dm.elements.size()) == doctest::Approx(o.size / 2).epsilon(0.25));
  CHECK(std::all_of(dm.elements.begin(), dm.elements.end(), [&](Index i) { return i >= 0 && i < static_cast<Index>(dm.xyz.size()); }));
  CHECK(dm.report.scaled_jacobian_min > 0);
  for (size_t e = 0; e < dm.elements.size() / 4; ++e) CHECK(signed_area_uv(dm, e) > 0);
  // Interior nodes lie on the triangulation; the boundary's midpoints on the chords between their
  // neighbours, off the curved sides by a segment's sag only.
  meshing::DomainMesh inside = dm;
  inside.xyz.erase(inside.xyz.begin(), inside.xyz.begin() + dm.boundary_nodes);
  CHECK(test::max_off_surface(f.mesh(), inside) <= 1e-9);
  CHECK(test::max_off_surface(f.mesh(), dm) <= 3e-3);
  check_conforming(dm);
}

TEST_CASE("quads from caller edge nodes: the given nodes stay, and all-quad adds the same midpoints on either side") {
  const auto f = test::solved(test::unit_square(4));
  const Topology& tp = f.topo();
  REQUIRE(tp.edges.size() == 1);
  // Uneven nodes round the whole boundary, as a neighbouring face would give them: the chain from
  // the edge's vertex (0, 0) round by the corners, which stay nodes of their own.
  std::vector<Vec3> chain;
  meshing::EdgeNodes given;
  const int n = 11;
  for (int side = 0; side < 4; ++side)
    for (int k = 0; k < n; ++k) {
      const double s = static_cast<double>(k) / n, g = s * s * (3 - 2 * s);  // graded along each side
      const Vec3 p = side == 0 ? Vec3(g, 0, 0) : side == 1 ? Vec3(1, g, 0) : side == 2 ? Vec3(1 - g, 1, 0) : Vec3(0, 1 - g, 0);
      chain.push_back(p);
      if (k > 0) given[0].push_back(p);
    }
  chain.push_back(Vec3(0, 0, 0));
  meshing::MeshOptions o;
  o.size = 0.08;
  o.elements = meshing::Elements::Quads;
  const auto dm = f.mesh_domain(o, given);
  REQUIRE(dm.nodes_per_element == 4);
  // Each given node, and each midpoint of two consecutive given nodes, is a boundary node.
  auto has = [&](const Vec3& p) {
    for (Index k = 0; k < dm.boundary_nodes; ++k)
      if ((dm.xyz[static_cast<size_t>(k)] - p).norm() < 1e-12) return true;
    return false;
  };
  for (size_t k = 0; k + 1 < chain.size(); ++k) {
    CHECK(has(chain[k]));
    CHECK(has(0.5 * (chain[k] + chain[k + 1])));
  }
  CHECK(dm.boundary_nodes == static_cast<Index>(2 * (chain.size() - 1)));
  check_conforming(dm);
}

TEST_CASE("an unknown element kind is refused") {
  const auto f = test::solved(test::unit_square(4));
  meshing::MeshOptions o;
  o.size = 0.2;
  o.elements = static_cast<meshing::Elements>(7);
  CHECK_THROWS_AS(f.mesh_domain(o), Error);
}

TEST_CASE("max_elements caps the all-quad mesh's quads, not only the triangles before the split") {
  const auto f = test::solved(test::unit_square(4));
  meshing::MeshOptions o;
  o.size = 0.1;
  o.elements = meshing::Elements::Quads;
  const auto quads = f.mesh_domain(o);
  // Enough for the triangles the quads are split from (about half as many), not for the quads.
  o.max_elements = quads.report.elements - 1;
  CHECK_THROWS_AS(f.mesh_domain(o), Error);
  o.max_elements = quads.report.elements;
  CHECK(f.mesh_domain(o).report.elements == quads.report.elements);
}

TEST_CASE("quad smoothing unfolds: interior nodes of an all-quad mesh thrown about come back as quads convex in UV and unfolded in 3D") {
  const auto f = test::solved(test::saddle(24), 1.0);
  meshing::MeshOptions o;
  o.size = 0.1;
  o.elements = meshing::Elements::Quads;
  meshing::DomainMesh dm = f.mesh_domain(o);
  REQUIRE(dm.report.scaled_jacobian_min > 0);
  const meshing::SurfaceMap map(f.mesh(), f.topo(), f.uv());
  std::vector<double> shortest(dm.uv.size(), 1e300);
  for (size_t e = 0; e < dm.elements.size(); e += 4)
    for (size_t k = 0; k < 4; ++k) {
      const auto a = static_cast<size_t>(dm.elements[e + k]), b = static_cast<size_t>(dm.elements[e + (k + 1) % 4]);
      const double d = (dm.uv[a] - dm.uv[b]).norm();
      shortest[a] = std::min(shortest[a], d), shortest[b] = std::min(shortest[b], d);
    }
  auto folded = [&] {
    int n = 0;
    for (size_t e = 0; e < dm.elements.size() / 4; ++e) {
      auto X = [&](size_t k) { return dm.xyz[static_cast<size_t>(dm.elements[4 * e + k])]; };
      n += !(signed_area_uv(dm, e) > 0) || !(meshing::scaled_jacobian(X(0), X(1), X(2), X(3)) > 0);
    }
    return n;
  };
  // Each interior node moved by up to 1.5 times its shortest edge, the same pseudo-random way each
  // run: most quads fold or turn over. Two smoothing passes left one of them folded before the
  // rounds that unfold what the passes leave (each node's search was held by its neighbours' floor).
  std::uint64_t state = 12345;
  auto next = [&] {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state >> 11) / 9007199254740992.0;
  };
  for (size_t i = static_cast<size_t>(dm.boundary_nodes); i < dm.uv.size(); ++i) {
    const double angle = 2 * 3.14159265358979 * next(), r = 1.5 * shortest[i] * next();
    dm.uv[i] += r * meshing::P2(std::cos(angle), std::sin(angle));
    map.lift(dm.uv[i], dm.xyz[i], &dm.normal[i]);
  }
  const int before = folded();
  meshing::smooth_quads(dm, map, 2, false);
  const int after = folded();
  MESSAGE("quads folded or not convex in UV: ", before, " of ", dm.elements.size() / 4, " thrown about, ", after, " after two smoothing passes");
  CHECK(2 * before > static_cast<int>(dm.elements.size() / 4));
  CHECK(after == 0);
}

TEST_CASE("all-quad split: where the domain stretches unevenly, new nodes lift to the 3D midpoints and centres, and the quads stay square") {
  // A flat unit square whose domain is u^3 by v: the UV middle of an element lifts far to the right
  // of its 3D middle, as across a pinch of a face or its sliver facets. Two 3D squares side by side
  // (0.4 wide) share an edge inside the face, whose middle moves along it; their centres move freely.
  const TriMesh mesh = test::unit_square(32);
  const Topology topo = build_topology(mesh, TopologySpec{});
  VectorXc uv(static_cast<Eigen::Index>(topo.use_vertex.size()));
  for (size_t u = 0; u < topo.use_vertex.size(); ++u) {
    const Vec3& x = mesh.vertices[static_cast<size_t>(topo.use_vertex[u])];
    uv[static_cast<Eigen::Index>(u)] = Complex(x.x() * x.x() * x.x(), x.y());
  }
  const meshing::SurfaceMap map(mesh, topo, uv);
  meshing::DomainMesh start;
  const double xs[3] = {0.1, 0.5, 0.9}, ys[2] = {0.1, 0.5};
  for (double y : ys)
    for (double x : xs) {
      start.uv.emplace_back(x * x * x, y);
      start.xyz.emplace_back(x, y, 0.0);
      start.normal.emplace_back(0.0, 0.0, 1.0);
    }
  start.nodes_per_element = 4;
  start.elements = {0, 1, 4, 3, 1, 2, 5, 4};
  start.boundary_nodes = 6;  // every corner is on the boundary of the two squares
  auto centre_offset_and_worst = [&](meshing::SplitNodes place, double& worst) {
    meshing::DomainMesh m = start;
    meshing::split_into_quads(m, map, place);
    REQUIRE(m.elements.size() == 8 * 4);
    worst = 2;
    for (size_t e = 0; e < m.elements.size() / 4; ++e) {
      auto X = [&](size_t k) { return m.xyz[static_cast<size_t>(m.elements[4 * e + k])]; };
      CHECK(signed_area_uv(m, e) > 0);
      worst = std::min(worst, meshing::scaled_jacobian(X(0), X(1), X(2), X(3)));
    }
    // The new nodes inside: the shared edge's middle (3D (0.5, 0.3)) and the two centres (3D
    // (0.3, 0.3) and (0.7, 0.3)); the farthest of them from its place.
    double off = 0;
    for (size_t i = static_cast<size_t>(m.boundary_nodes); i < m.xyz.size(); ++i) {
      double nearest = 1e300;
      for (double x : {0.3, 0.5, 0.7}) nearest = std::min(nearest, (m.xyz[i] - Vec3(x, 0.3, 0)).norm());
      off = std::max(off, nearest);
    }
    CHECK(m.xyz.size() - static_cast<size_t>(m.boundary_nodes) == 3);
    return off;
  };
  double worst_uv = 0, worst_3d = 0;
  const double off_uv = centre_offset_and_worst(meshing::SplitNodes::uv_middles, worst_uv);
  const double off_3d = centre_offset_and_worst(meshing::SplitNodes::nearest_3d, worst_3d);
  MESSAGE("new nodes off their 3D places: ", off_uv, " at the UV middles, ", off_3d, " nearest in 3D; worst scaled Jacobian ", worst_uv,
          " and ", worst_3d);
  CHECK(off_uv > 0.05);
  CHECK(off_3d < 1e-6);
  CHECK(worst_uv < 0.95);
  CHECK(worst_3d > 0.999);
}
