// Hard edges inside a face (METHOD §9.6): a scar, a repeated edge kept closed, is an edge of the
// mesh in every element kind, its nodes shared by the elements on both sides.
#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "mesh_faces.hpp"

using namespace wefm;

namespace {

constexpr int kCells = 40;

// A gently curved plate over a 40 x 40 grid with three slits along grid rows: two inside the face,
// one from the left side in. In 3D a point lies on slit k exactly when its y is the row's.
struct SlitPlate {
  TriMesh mesh;
  std::vector<std::pair<Index, Index>> seams;
  std::vector<double> row;               // y of each slit
  std::vector<std::pair<double, double>> span;  // x range of each slit
};

SlitPlate slit_plate() {
  SlitPlate p;
  p.mesh = test::grid(kCells, kCells, [](double u, double v) { return Vec3(u, v, 0.15 * std::sin(3 * u) * std::cos(2 * v)); });
  auto id = [](int i, int j) { return static_cast<Index>(j * (kCells + 1) + i); };
  const int slits[3][3] = {{8, 28, 8}, {12, 30, 20}, {0, 16, 31}};  // first cell, last cell + 1, row
  for (const auto& s : slits) {
    for (int i = s[0]; i < s[1]; ++i) p.seams.emplace_back(id(i, s[2]), id(i + 1, s[2]));
    p.row.push_back(static_cast<double>(s[2]) / kCells);
    p.span.emplace_back(static_cast<double>(s[0]) / kCells, static_cast<double>(s[1]) / kCells);
  }
  return p;
}

}  // namespace

TEST_CASE("a scar stays an edge of the mesh in every element kind, its nodes shared by both sides") {
  const SlitPlate plate = slit_plate();
  const auto f = test::solved(plate.mesh, 1.0, plate.seams, EdgeMode::Scar);
  for (const auto kind : {meshing::Elements::Triangles, meshing::Elements::QuadDominant, meshing::Elements::Quads}) {
    CAPTURE(static_cast<int>(kind));
    meshing::MeshOptions o;
    o.size = 0.05;
    o.elements = kind;
    const auto dm = f.mesh_domain(o);
    const auto edges = test::directed_edges(dm);
    // Conforming: each directed edge once; one way round only on the plate's outer sides.
    for (const auto& [e, n] : edges) {
      CHECK(n == 1);
      if (!edges.count({e.second, e.first})) {
        const Vec3 &a = dm.xyz[static_cast<size_t>(e.first)], &b = dm.xyz[static_cast<size_t>(e.second)];
        const Vec3 mid = 0.5 * (a + b);
        CHECK(std::min({mid.x(), mid.y(), 1 - mid.x(), 1 - mid.y()}) < 1e-9);
      }
    }
    // No two nodes at one point: the scar's sides were merged, not meshed apart.
    std::vector<Vec3> pts = dm.xyz;
    std::sort(pts.begin(), pts.end(), [](const Vec3& a, const Vec3& b) { return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3); });
    for (size_t k = 1; k < pts.size(); ++k) CHECK((pts[k] - pts[k - 1]).norm() > 1e-9);
    // Along each slit, its nodes in order of x: every two neighbours are an edge used both ways
    // round, one element on each side, and together they run the slit's whole length.
    for (size_t s = 0; s < plate.row.size(); ++s) {
      CAPTURE(s);
      std::vector<std::pair<double, Index>> on;
      for (size_t k = 0; k < dm.xyz.size(); ++k) {
        const Vec3& x = dm.xyz[k];
        if (std::abs(x.y() - plate.row[s]) < 1e-12 && x.x() > plate.span[s].first - 1e-12 && x.x() < plate.span[s].second + 1e-12)
          on.emplace_back(x.x(), static_cast<Index>(k));
      }
      std::sort(on.begin(), on.end());
      REQUIRE(on.size() >= 5);
      CHECK(on.front().first == doctest::Approx(plate.span[s].first).epsilon(1e-12));
      CHECK(on.back().first == doctest::Approx(plate.span[s].second).epsilon(1e-12));
      for (size_t k = 0; k + 1 < on.size(); ++k) {
        CHECK(edges.count({on[k].second, on[k + 1].second}) == 1);
        CHECK(edges.count({on[k + 1].second, on[k].second}) == 1);
      }
      // The nodes stay where the boundary put them: never moved off the slit.
      for (const auto& [x, k] : on) CHECK(k < dm.boundary_nodes);
    }
    if (kind != meshing::Elements::Triangles) {
      CHECK(dm.report.quad_area_fraction >= (kind == meshing::Elements::Quads ? 1.0 : 0.9));
      CHECK(dm.report.scaled_jacobian_min >= 0.3);
    }
    CHECK(dm.hard_edges.size() >= 3 * 5);
  }
}
