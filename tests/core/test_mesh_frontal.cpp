// Frontal-Delaunay free meshing (frontal.hpp, size_field.hpp): quality on simple faces, the
// boundary left alone, grading from short boundary segments, a valid triangulation throughout.
#include "mesh_faces.hpp"
#include "wefm/core/meshing/frontal.hpp"
#include "wefm/core/meshing/graded_spacing.hpp"
#include "wefm/core/meshing/mesh_quality.hpp"
#include "wefm/core/meshing/node_optimisation.hpp"

using namespace wefm;
using meshing::P2;

namespace {

double mean_edge(const meshing::DomainMesh& dm) {
  double s = 0;
  for (size_t e = 0; e < dm.elements.size(); e += 3)
    for (size_t k = 0; k < 3; ++k) s += (dm.xyz[static_cast<size_t>(dm.elements[e + k])] - dm.xyz[static_cast<size_t>(dm.elements[e + (k + 1) % 3])]).norm();
  return s / static_cast<double>(dm.elements.size());
}

// Every UV element counter-clockwise, and the boundary nodes exactly the loop discretisation.
void check_domain_mesh(const test::SolvedFace& f, const meshing::MeshOptions& o, const meshing::DomainMesh& dm,
                       const meshing::EdgeNodes& given = {}) {
  for (size_t e = 0; e < dm.elements.size(); e += 3)
    CHECK(meshing::orient2d(dm.uv[static_cast<size_t>(dm.elements[e])], dm.uv[static_cast<size_t>(dm.elements[e + 1])],
                            dm.uv[static_cast<size_t>(dm.elements[e + 2])]) > 0);
  const auto loops = meshing::discretise_loops(f.mesh(), f.topo(), f.uv(), o.size, o.corner_angle_deg * kPi / 180.0, given,
                                               meshing::kSizeGradation);
  size_t k = 0;
  for (const auto& l : loops)
    for (size_t j = 0; j < l.uv.size(); ++j, ++k) {
      REQUIRE(k < static_cast<size_t>(dm.boundary_nodes));
      CHECK(dm.uv[k] == l.uv[j]);
      CHECK(dm.xyz[k] == l.xyz[j]);
    }
  CHECK(k == static_cast<size_t>(dm.boundary_nodes));
  CHECK(dm.report.outside_nodes == 0);
  CHECK(test::max_off_surface(f.mesh(), dm) <= 1e-9);
}

}  // namespace

TEST_CASE("frontal free meshing of a flat square: near-equilateral elements of size h, boundary untouched") {
  const auto f = test::solved(test::unit_square(8));
  meshing::MeshOptions o;
  o.size = 0.05;
  const auto dm = f.mesh_domain(o);
  MESSAGE("square: ", dm.report.elements, " triangles, lambda_mesh ", dm.report.lambda_mesh, ", min ", dm.report.lambda_min);
  CHECK(dm.report.lambda_mesh >= 0.985);
  CHECK(dm.report.lambda_min >= 0.75);
  // Equilateral triangles of side h tile the unit square in 4 / (sqrt(3) h^2) of them.
  CHECK(static_cast<double>(dm.report.elements) == doctest::Approx(4 / (std::sqrt(3.0) * o.size * o.size)).epsilon(0.1));
  CHECK(mean_edge(dm) == doctest::Approx(o.size).epsilon(0.1));
  check_domain_mesh(f, o, dm);
}

TEST_CASE("frontal free meshing of a half cylinder: the size and shape hold in 3D") {
  const auto f = test::solved(test::cut_cylinder(24, 12, 1.0, 2.0, kPi), 1.0);
  meshing::MeshOptions o;
  o.size = 0.1;
  const auto dm = f.mesh_domain(o);
  MESSAGE("half cylinder: ", dm.report.elements, " triangles, lambda_mesh ", dm.report.lambda_mesh, ", min ", dm.report.lambda_min);
  CHECK(dm.report.lambda_mesh >= 0.985);
  CHECK(dm.report.lambda_min >= 0.75);
  CHECK(mean_edge(dm) == doctest::Approx(o.size).epsilon(0.1));
  check_domain_mesh(f, o, dm);
}

TEST_CASE("frontal free meshing of a curved face whose domain scale varies: sizes measured in 3D") {
  // A spherical rectangle: its flattening stretches the domain, so UV sizes differ from 3D ones.
  const auto f = test::solved(test::hemisphere(24, 12), 1.0);
  meshing::MeshOptions o;
  o.size = 0.08;
  const auto dm = f.mesh_domain(o);
  MESSAGE("spherical rectangle: ", dm.report.elements, " triangles, lambda_mesh ", dm.report.lambda_mesh, ", min ", dm.report.lambda_min);
  CHECK(dm.report.lambda_mesh >= 0.98);
  CHECK(dm.report.lambda_min >= 0.75);
  CHECK(mean_edge(dm) == doctest::Approx(o.size).epsilon(0.1));
  check_domain_mesh(f, o, dm);
}

TEST_CASE("a side discretised at h/4 grades the inside down to it instead of standing h-sized elements on it") {
  const auto f = test::solved(test::unit_square(8));
  REQUIRE(f.topo().edges.size() == 1);
  // The square's one edge: the side y = 0 at h/4, the three others at h (nodes in loop order).
  meshing::EdgeNodes given;
  const double h = 0.1;
  auto& nodes = given[0];
  for (int k = 1; k < 40; ++k) nodes.emplace_back(k / 40.0, 0, 0);
  for (int k = 0; k < 10; ++k) nodes.emplace_back(1, k / 10.0, 0);
  for (int k = 0; k < 10; ++k) nodes.emplace_back(1 - k / 10.0, 1, 0);
  for (int k = 0; k < 10; ++k) nodes.emplace_back(0, 1 - k / 10.0, 0);
  meshing::MeshOptions o;
  o.size = h;
  const auto dm = f.mesh_domain(o, given);
  MESSAGE("graded square: ", dm.report.elements, " triangles, lambda_mesh ", dm.report.lambda_mesh, ", min ", dm.report.lambda_min);
  CHECK(dm.report.lambda_min >= 0.5);
  CHECK(dm.report.lambda_mesh >= 0.95);
  // Elements next to the fine side are near its spacing; far from it, near h.
  double near = 0, far = 0;
  int n_near = 0, n_far = 0;
  for (size_t e = 0; e < dm.elements.size(); e += 3) {
    const Vec3 &a = dm.xyz[static_cast<size_t>(dm.elements[e])], &b = dm.xyz[static_cast<size_t>(dm.elements[e + 1])],
               &c = dm.xyz[static_cast<size_t>(dm.elements[e + 2])];
    const double y = (a.y() + b.y() + c.y()) / 3, l = ((a - b).norm() + (b - c).norm() + (c - a).norm()) / 3;
    if (y < 0.03) near += l, ++n_near;
    if (y > 0.7) far += l, ++n_far;
  }
  REQUIRE(n_near > 0);
  REQUIRE(n_far > 0);
  CHECK(near / n_near < 0.45 * h);
  CHECK(far / n_far == doctest::Approx(h).epsilon(0.15));
  check_domain_mesh(f, o, dm, given);
}

TEST_CASE("the size field is h away from short segments and grows from them at the gradation") {
  meshing::LoopNodes l;
  // A square of side 1 with one side cut into 10 segments of 0.1 and the others single segments.
  for (int k = 0; k < 10; ++k) l.xyz.emplace_back(k / 10.0, 0, 0);
  l.xyz.emplace_back(1, 0, 0), l.xyz.emplace_back(1, 1, 0), l.xyz.emplace_back(0, 1, 0);
  l.uv.resize(l.xyz.size(), P2::Zero());
  const meshing::SizeField field({l}, 0.5, 0.3);
  CHECK(field.at(Vec3(0.55, 0, 0)) == doctest::Approx(0.1));
  CHECK(field.at(Vec3(0.55, 0.5, 0)) == doctest::Approx(0.1 + 0.3 * 0.5));
  CHECK(field.at(Vec3(0.5, 2, 0)) == doctest::Approx(0.5));
  CHECK(field.at(Vec3(1e3, 0, 0)) == doctest::Approx(0.5));
  // No segment below h: h everywhere.
  const meshing::SizeField flat({l}, 0.05, 0.3);
  CHECK(flat.at(Vec3(0.5, 0.5, 0)) == 0.05);
}

TEST_CASE("the size field equals the smallest l + g d over its sources, for a dense cluster among sparse segments") {
  // A loop of long segments round a spiral of thousands of tiny ones (text engraved on a face), and
  // a second loop far off: the field's search over boxes of sources must give the value of the
  // brute-force minimum, bit for bit, at points inside, beside and far from the cluster.
  meshing::LoopNodes spiral, frame, far_loop;
  for (int k = 0; k < 3000; ++k) {
    const double t = 0.01 * k, r = 0.2 + 0.0005 * k;
    spiral.xyz.emplace_back(r * std::cos(t), r * std::sin(t), 1e-4 * (k % 7));
  }
  for (const auto& p : {Vec3(-3, -3, 0), Vec3(3, -3, 0), Vec3(3, 3, 0), Vec3(-3, 3, 0)}) frame.xyz.push_back(p);
  for (int k = 0; k < 40; ++k) far_loop.xyz.emplace_back(50 + 0.05 * k, 0.3 * (k % 2), 0);
  for (auto* l : {&spiral, &frame, &far_loop}) l->uv.resize(l->xyz.size(), P2::Zero());
  const std::vector<meshing::LoopNodes> loops{spiral, frame, far_loop};
  const double h = 0.8, g = 0.3;
  const meshing::SizeField field(loops, h, g);
  std::uint64_t state = 12345;
  auto next = [&state] { state = state * 6364136223846793005ull + 1442695040888963407ull; return static_cast<double>(state >> 11) / 9007199254740992.0; };
  int below_h = 0;
  for (int q = 0; q < 2000; ++q) {
    const double spread = q % 3 == 0 ? 1.0 : q % 3 == 1 ? 4.0 : 60.0;
    const Vec3 x((2 * next() - 1) * spread, (2 * next() - 1) * spread, 0.1 * (2 * next() - 1));
    double best = h;
    for (const auto& l : loops) {
      const size_t n = l.xyz.size();
      for (size_t k = 0; k < n; ++k) {
        const Vec3 &a = l.xyz[k], &b = l.xyz[(k + 1) % n];
        const double len = (b - a).norm();
        if (!(len < 0.98 * h) || !(len > 0) || !(len < best)) continue;
        best = std::min(best, len + g * std::sqrt((x - 0.5 * (a + b)).squaredNorm()));
      }
    }
    CHECK(field.at(x) == best);
    below_h += best < h;
  }
  CHECK(below_h > 500);  // the points do reach the sources
}

TEST_CASE("frontal refinement leaves a valid constrained Delaunay triangulation, all of it at the size") {
  const auto f = test::solved(test::flat_patch(12));
  const double h = 0.08;
  const auto loops = meshing::discretise_loops(f.mesh(), f.topo(), f.uv(), h, kPi / 6, {});
  std::vector<P2> pts;
  std::vector<Vec3> xyz;
  std::vector<std::array<Index, 2>> segs;
  for (const auto& l : loops) {
    const Index base = static_cast<Index>(pts.size()), n = static_cast<Index>(l.uv.size());
    for (Index k = 0; k < n; ++k) pts.push_back(l.uv[static_cast<size_t>(k)]), xyz.push_back(l.xyz[static_cast<size_t>(k)]), segs.push_back({base + k, base + (k + 1) % n});
  }
  meshing::Triangulation tr(pts, segs);
  const meshing::SurfaceMap map(f.mesh(), f.topo(), f.uv());
  const meshing::SizeField field(loops, h, 0.3);
  std::vector<double> sizes(xyz.size());
  for (size_t k = 0; k < xyz.size(); ++k) sizes[k] = field.at(xyz[k]);
  int ticks = 0;
  const std::int64_t added = meshing::frontal_refine(tr, xyz, sizes, map, field, {}, [&] { ++ticks; });
  CHECK(added > 100);
  CHECK(ticks == added);
  CHECK(tr.valid());
  CHECK(xyz.size() == static_cast<size_t>(tr.node_count()));
  int large = 0;
  const auto tris = tr.triangles();
  for (const auto& t : tris)
    large += meshing::size_ratio(xyz[static_cast<size_t>(t[0])], xyz[static_cast<size_t>(t[1])], xyz[static_cast<size_t>(t[2])], h) >= 1.3;
  CHECK(large <= static_cast<int>(tris.size()) / 100);
  // The node cap is honoured.
  meshing::Triangulation capped(pts, segs);
  std::vector<Vec3> xyz2(xyz.begin(), xyz.begin() + static_cast<long>(pts.size()));
  std::vector<double> sizes2(sizes.begin(), sizes.begin() + static_cast<long>(pts.size()));
  meshing::FrontalSettings s;
  s.max_nodes = static_cast<std::int64_t>(pts.size()) + 20;
  meshing::frontal_refine(capped, xyz2, sizes2, map, field, s, [] {});
  CHECK(capped.node_count() == s.max_nodes);
  CHECK(capped.valid());
}

TEST_CASE("node optimisation raises the sum of log lambda, keeps the boundary and never inverts an element") {
  const auto f = test::solved(test::saddle(16), 1.0);
  meshing::MeshOptions o;
  o.size = 0.15;
  o.smoothing_iterations = 0;
  meshing::DomainMesh dm = f.mesh_domain(o);
  const meshing::SurfaceMap map(f.mesh(), f.topo(), f.uv());
  // Shake the interior nodes by a tenth of h (deterministically), staying inside their stars.
  std::vector<std::array<Index, 3>> tris;
  for (size_t e = 0; e < dm.elements.size(); e += 3) tris.push_back({dm.elements[e], dm.elements[e + 1], dm.elements[e + 2]});
  auto valid = [&] {
    for (const auto& t : tris)
      if (!(meshing::orient2d(dm.uv[static_cast<size_t>(t[0])], dm.uv[static_cast<size_t>(t[1])], dm.uv[static_cast<size_t>(t[2])]) > 0)) return false;
    return true;
  };
  for (Index v = dm.boundary_nodes; v < static_cast<Index>(dm.uv.size()); ++v) {
    const P2 keep = dm.uv[static_cast<size_t>(v)];
    const double a = 2.399963 * v;  // golden angle steps
    dm.uv[static_cast<size_t>(v)] += 0.01 * P2(std::cos(a), std::sin(a));
    Vec3 x;
    if (!valid() || !map.lift(dm.uv[static_cast<size_t>(v)], x)) dm.uv[static_cast<size_t>(v)] = keep;
    map.lift(dm.uv[static_cast<size_t>(v)], dm.xyz[static_cast<size_t>(v)]);
  }
  REQUIRE(valid());
  auto stats = [&](double& sum, double& worst) {
    sum = 0, worst = 1;
    for (const auto& t : tris) {
      const double l = meshing::lo_lambda(dm.xyz[static_cast<size_t>(t[0])], dm.xyz[static_cast<size_t>(t[1])], dm.xyz[static_cast<size_t>(t[2])]);
      sum += std::log(l), worst = std::min(worst, l);
    }
  };
  double sum0, worst0, sum1, worst1;
  stats(sum0, worst0);
  const std::vector<P2> boundary(dm.uv.begin(), dm.uv.begin() + dm.boundary_nodes);
  const std::int64_t moves = meshing::optimise_nodes(dm.uv, dm.xyz, tris, dm.boundary_nodes, map, 0.8);
  stats(sum1, worst1);
  MESSAGE("moves ", moves, ": lambda_mesh ", std::exp(sum0 / tris.size()), " -> ", std::exp(sum1 / tris.size()), ", min ", worst0, " -> ", worst1);
  CHECK(moves > 0);
  CHECK(sum1 > sum0);
  CHECK(worst1 >= std::min(worst0, 0.8) - 1e-12);
  CHECK(valid());
  for (size_t k = 0; k < boundary.size(); ++k) CHECK(dm.uv[k] == boundary[k]);
  CHECK(test::max_off_surface(f.mesh(), dm) <= 1e-9);
}

TEST_CASE("graded spacing: uniform away from short ends, shrinking to them, the same from either end") {
  const auto uniform = meshing::graded_spacing(1.0, 0.1, 0.2, 0.2, 0.3, 1);
  REQUIRE(uniform.size() == 10);
  for (size_t k = 0; k < uniform.size(); ++k) CHECK(uniform[k] == doctest::Approx(0.1 * static_cast<double>(k)));
  const auto g = meshing::graded_spacing(1.0, 0.1, 0.02, 0.1, 0.3, 1);
  REQUIRE(g.size() > 10);
  CHECK(g[1] == doctest::Approx(0.02).epsilon(0.3));
  for (size_t k = 1; k < g.size(); ++k) {
    const double seg = g[k] - g[k - 1], next = (k + 1 < g.size() ? g[k + 1] : 1.0) - g[k];
    CHECK(seg > 0);
    CHECK(next / seg <= 1.45);
    CHECK(next <= 0.1 * 1.05);
  }
  // Reversed ends: the mirror image.
  const auto r = meshing::graded_spacing(1.0, 0.1, 0.1, 0.02, 0.3, 1);
  REQUIRE(r.size() == g.size());
  for (size_t k = 1; k < g.size(); ++k) CHECK(1.0 - r[g.size() - k] == doctest::Approx(g[k]).epsilon(1e-9));
  CHECK(meshing::graded_spacing(1.0, 0.1, 0.02, 0.1, 0.3, 40).size() == 40);  // the count floor
}

TEST_CASE("a short boundary piece: the long pieces next to it grade down to it") {
  // A quadrilateral (0,0) (1,0) (1,1) (0,0.05): its left side is h/2 long at h = 0.1.
  const auto f = test::solved(test::grid(20, 20, [](double u, double v) { return Vec3(u, v * (0.05 + 0.95 * u), 0.0); }));
  meshing::MeshOptions o;
  o.size = 0.1;
  const auto dm = f.mesh_domain(o);
  MESSAGE("short side: ", dm.report.elements, " triangles, lambda_mesh ", dm.report.lambda_mesh, ", min ", dm.report.lambda_min);
  // Uniform pieces: 0.69 (an h-long segment at the short side's corner).
  CHECK(dm.report.lambda_min >= 0.75);
  CHECK(dm.report.lambda_mesh >= 0.95);
  // The boundary segments that end at the short side's corners are near its length, not h.
  for (Index k = 0; k < dm.boundary_nodes; ++k) {
    const Vec3& a = dm.xyz[static_cast<size_t>(k)];
    const Vec3& b = dm.xyz[static_cast<size_t>((k + 1) % dm.boundary_nodes)];
    if (std::min(a.x(), b.x()) == 0 && std::max(a.x(), b.x()) > 0) CHECK((a - b).norm() < 0.08);
  }
  check_domain_mesh(f, o, dm);
}
