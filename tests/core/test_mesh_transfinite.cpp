// Transfinite meshing (METHOD §9): exact on developable four-sided domains.
#include "mesh_faces.hpp"
#include "wefm/core/meshing/mesh_quality.hpp"
#include "wefm/core/meshing/transfinite.hpp"

using namespace wefm;

TEST_CASE("a flat square meshed transfinite gives wiggle 0 and scaled Jacobians 1") {
  const auto f = test::solved(test::unit_square(8));
  meshing::MeshOptions o;
  o.type = meshing::MeshType::Transfinite;
  o.size = 0.1;
  const auto dm = f.mesh_domain(o);
  CHECK(dm.nodes_per_element == 4);
  CHECK(dm.report.elements == 100);
  CHECK(dm.report.wiggle_max < 1e-20);
  CHECK(dm.report.scaled_jacobian_min == doctest::Approx(1.0).epsilon(1e-12));
  CHECK(dm.report.lambda_min == doctest::Approx(std::sqrt(3.0) / 2).epsilon(1e-9));  // right isosceles halves
  CHECK(test::max_off_surface(f.mesh(), dm) <= 1e-9);
  CHECK(dm.report.outside_nodes == 0);
}

TEST_CASE("a cut cylinder with a periodic seam meshed transfinite gives wiggle below 1e-6") {
  std::vector<std::pair<Index, Index>> seam;
  const TriMesh m = test::open_cylinder(24, 8, &seam);
  const auto f = test::solved(m, 0.0, seam, EdgeMode::Periodic);
  meshing::MeshOptions o;
  o.type = meshing::MeshType::Transfinite;
  o.size = 2 * std::sin(kPi / 24);  // one node per facet column: the nodes fall on the facet vertices
  const auto dm = f.mesh_domain(o);
  CHECK(dm.report.elements == 24 * 8);
  CHECK(dm.report.wiggle_max < 1e-6);
  CHECK(dm.report.scaled_jacobian_min > 0.999);
  CHECK(test::max_off_surface(f.mesh(), dm) <= 1e-9);
  // The seam's two sides are opposite sides of the grid (which pair depends on the first corner):
  // node by node the same 3D points.
  const size_t cols = static_cast<size_t>(dm.grid_columns), rows = dm.xyz.size() / cols;
  double first_last_row = 0, first_last_col = 0;
  for (size_t i = 0; i < cols; ++i) first_last_row = std::max(first_last_row, (dm.xyz[i] - dm.xyz[(rows - 1) * cols + i]).norm());
  for (size_t j = 0; j < rows; ++j) first_last_col = std::max(first_last_col, (dm.xyz[j * cols] - dm.xyz[j * cols + cols - 1]).norm());
  CHECK(std::min(first_last_row, first_last_col) < 1e-12);
  CHECK(dm.rails.size() == (rows - 2) + (cols - 2));
}

TEST_CASE("transfinite meshing splits quads into triangles on request and honours given corners") {
  const auto f = test::solved(test::unit_square(6));
  meshing::MeshOptions o;
  o.type = meshing::MeshType::Transfinite;
  o.size = 0.25;
  o.quads = false;
  const auto dm = f.mesh_domain(o);
  CHECK(dm.nodes_per_element == 3);
  CHECK(dm.report.elements == 32);
  const auto& lu = f.topo().loop_uses[0];
  o.corners = {lu[0], lu[1], lu[2], lu[3]};  // not a quadrilateral: all but one corner in a row
  CHECK_NOTHROW(f.mesh_domain(o));
  o.corners = {lu[0], lu[0], lu[2], lu[3]};
  CHECK_THROWS_AS(f.mesh_domain(o), Error);
}

TEST_CASE("transfinite meshing takes caller-given edge nodes as its sides' nodes") {
  const auto f = test::solved(test::unit_square(4));
  REQUIRE(f.topo().edges.size() == 1);
  // Uneven nodes on the square's only edge, in its direction; the corners stay nodes (they turn).
  meshing::EdgeNodes given;
  given[0] = {Vec3(0.1, 0, 0), Vec3(0.3, 0, 0), Vec3(0.7, 0, 0), Vec3(1, 0.5, 0),
              Vec3(0.8, 1, 0), Vec3(0.5, 1, 0), Vec3(0.2, 1, 0), Vec3(0, 0.5, 0)};
  meshing::MeshOptions o;
  o.type = meshing::MeshType::Transfinite;
  o.size = 0.1;  // ignored along given edges: the grid follows the given nodes
  const auto dm = f.mesh_domain(o, given);
  CHECK(dm.report.elements == 4 * 2);
  int found = 0;
  for (const Vec3& g : given[0])
    for (const Vec3& x : dm.xyz) found += x == g ? 1 : 0;  // bit for bit, as the neighbours have them
  CHECK(found == 8);
  CHECK(dm.report.scaled_jacobian_min > 0.5);
  CHECK(test::max_off_surface(f.mesh(), dm) <= 1e-9);
  // Opposite sides with different counts have no grid between them.
  given[0].erase(given[0].begin() + 5);
  try {
    f.mesh_domain(o, given);
    FAIL("expected Error(unsupported)");
  } catch (const Error& e) {
    CHECK(e.code() == Errc::unsupported);
  }
}

TEST_CASE("transfinite meshing refuses a face with holes") {
  const auto f = test::solved(test::disk_with_holes());
  meshing::MeshOptions o;
  o.type = meshing::MeshType::Transfinite;
  o.size = 0.1;
  CHECK_THROWS_AS(f.mesh_domain(o), Error);
}

TEST_CASE("the wiggle factor sees waviness in the surface and ignores bending with it") {
  std::vector<Vec3> x, n(9, Vec3(0, 0, 1)), bent;
  for (int j = 0; j <= 8; ++j) {
    x.emplace_back(j, 0.1 * (j % 2), 0);
    bent.emplace_back(j, 0, 0.1 * (j % 2));
  }
  CHECK(meshing::wiggle(x, n) == doctest::Approx(0.04 * 7 / 8 / std::pow((8 * std::sqrt(1.01)) / 8, 2)).epsilon(1e-9));
  CHECK(meshing::wiggle(bent, n) == doctest::Approx(0.0));
}

TEST_CASE("all-quad transfinite halves the grid both ways: the old nodes kept, the rim's new ones at the chords' middles") {
  const auto f = test::solved(test::saddle(24), 1.0);
  meshing::MeshOptions o;
  o.type = meshing::MeshType::Transfinite;
  o.size = 0.25;
  const auto coarse = f.mesh_domain(o);
  o.elements = meshing::Elements::Quads;
  const auto fine = f.mesh_domain(o);
  REQUIRE(fine.nodes_per_element == 4);
  const size_t c0 = static_cast<size_t>(coarse.grid_columns), r0 = coarse.xyz.size() / c0;
  const size_t c1 = static_cast<size_t>(fine.grid_columns), r1 = fine.xyz.size() / c1;
  CHECK(c1 == 2 * c0 - 1);
  CHECK(r1 == 2 * r0 - 1);
  CHECK(fine.report.elements == 4 * coarse.report.elements);
  CHECK(fine.report.quads == fine.report.elements);
  for (size_t j = 0; j < r0; ++j)
    for (size_t i = 0; i < c0; ++i) CHECK((fine.xyz[2 * j * c1 + 2 * i] - coarse.xyz[j * c0 + i]).norm() <= 1e-12);
  // Along the bottom and left sides: each new node is the middle of its two old neighbours' chord.
  for (size_t i = 0; i + 1 < c0; ++i) CHECK(fine.xyz[2 * i + 1] == 0.5 * (coarse.xyz[i] + coarse.xyz[i + 1]));
  for (size_t j = 0; j + 1 < r0; ++j) CHECK(fine.xyz[(2 * j + 1) * c1] == 0.5 * (coarse.xyz[j * c0] + coarse.xyz[(j + 1) * c0]));
  // Inside, the new nodes lie on the surface; the rails are the fine grid's and measured.
  meshing::DomainMesh inside = fine;
  inside.xyz.clear();
  for (size_t j = 1; j + 1 < r1; ++j)
    for (size_t i = 1; i + 1 < c1; ++i) inside.xyz.push_back(fine.xyz[j * c1 + i]);
  CHECK(test::max_off_surface(f.mesh(), inside) <= 1e-9);
  CHECK(fine.rails.size() == (r1 - 2) + (c1 - 2));
  CHECK(fine.report.wiggle_max < coarse.report.wiggle_max + 0.01);
  CHECK(fine.report.scaled_jacobian_min > 0.5);
}

TEST_CASE("automatic meshing: a grid on a four-sided domain, a free mesh on any other with the reason, never an error for unlike sides") {
  using meshing::AutomaticFallback;
  meshing::MeshOptions o;
  o.type = meshing::MeshType::Automatic;
  o.size = 0.1;
  // A square: four corners of 90 degrees.
  const auto square = test::solved(test::unit_square(8));
  const auto grid = square.mesh_domain(o);
  CHECK(grid.report.transfinite);
  CHECK(grid.report.automatic_fallback == AutomaticFallback::None);
  CHECK(grid.nodes_per_element == 4);
  CHECK(grid.report.elements == 100);
  CHECK(grid.report.scaled_jacobian_min == doctest::Approx(1.0).epsilon(1e-12));
  // A cut cone's domain (two straight sides, two arcs of small turns): four-sided too.
  const auto cone = test::solved(test::cut_cone(24, 8));
  CHECK(cone.mesh_domain(o).report.transfinite);
  // Holes, or one smooth loop: free triangles, as asked for by `elements`.
  // A disk: a grid squeezed onto it (the square's corners land on the circle, where it does not turn).
  const TriMesh disk = test::grid(16, 16, [](double u, double v) {
    const double x = 2 * u - 1, y = 2 * v - 1;
    return Vec3(x * std::sqrt(1 - y * y / 2), y * std::sqrt(1 - x * x / 2), 0.0);
  });
  for (const TriMesh& m : {test::disk_with_holes(), disk}) {
    const auto free = test::solved(m).mesh_domain(o);
    CHECK_FALSE(free.report.transfinite);
    CHECK(free.report.automatic_fallback == AutomaticFallback::NotFourSided);
    CHECK(free.nodes_per_element == 3);
    CHECK(free.report.lambda_min > 0.3);
  }
  // Caller nodes with unlike counts on opposite sides: the grid is impossible, the free mesh is not.
  meshing::EdgeNodes given;
  given[0] = {Vec3(0.1, 0, 0), Vec3(0.3, 0, 0), Vec3(0.7, 0, 0), Vec3(1, 0.5, 0), Vec3(0.5, 1, 0), Vec3(0.2, 1, 0), Vec3(0, 0.5, 0)};
  const auto unlike = test::solved(test::unit_square(4)).mesh_domain(o, given);
  CHECK_FALSE(unlike.report.transfinite);
  CHECK(unlike.report.automatic_fallback == AutomaticFallback::GridRefused);
  CHECK(unlike.report.elements > 0);
}

TEST_CASE("automatic meshing honours the caller's corners: the grid on them where it is good, else the free mesh and the grid's worst quad") {
  using meshing::AutomaticFallback;
  const auto square = test::solved(test::unit_square(8));
  const auto& loop = square.topo().loop_uses[static_cast<size_t>(square.topo().outer_loop)];
  const auto found = meshing::four_corners(square.topo(), square.uv());
  REQUIRE(found);
  meshing::MeshOptions o;
  o.type = meshing::MeshType::Automatic;
  o.size = 0.1;
  // The square's own corners, given from the second: the same grid, its first corner moved.
  for (size_t k = 0; k < 4; ++k) o.corners[k] = loop[(*found)[(k + 1) % 4]];
  const auto grid = square.mesh_domain(o);
  CHECK(grid.report.transfinite);
  CHECK(grid.report.elements == 100);
  CHECK(grid.report.scaled_jacobian_min == doctest::Approx(1.0).epsilon(1e-12));
  // Four corners on one side, given: the grid on them folds at the square's corners (the detected
  // corners would never be these), so the free mesh is made, and the report says why.
  const size_t first = (*found)[0];
  for (size_t k = 0; k < 4; ++k) o.corners[k] = loop[(first + k) % loop.size()];
  const auto poor = square.mesh_domain(o);
  CHECK_FALSE(poor.report.transfinite);
  CHECK(poor.report.automatic_fallback == AutomaticFallback::PoorGrid);
  CHECK(poor.report.refused_grid_scaled_jacobian_min < 0.3);
  CHECK(poor.nodes_per_element == 3);
  CHECK(poor.report.lambda_min > 0.3);
  // Corners given on a face with holes: not four-sided, the free mesh.
  const auto holes = test::solved(test::disk_with_holes());
  const auto& hloop = holes.topo().loop_uses[static_cast<size_t>(holes.topo().outer_loop)];
  for (size_t k = 0; k < 4; ++k) o.corners[k] = hloop[k * hloop.size() / 4];
  const auto free = holes.mesh_domain(o);
  CHECK_FALSE(free.report.transfinite);
  CHECK(free.report.automatic_fallback == AutomaticFallback::NotFourSided);
  // Corners that are not uses of the outer loop: an error, as for a transfinite mesh.
  o.corners = {loop[0], loop[1], loop[2], 1 << 30};
  try {
    square.mesh_domain(o);
    FAIL("expected Error(invalid_argument)");
  } catch (const Error& e) {
    CHECK(e.code() == Errc::invalid_argument);
  }
}
