// Interior slits: repeated edges whose both ends are inside the face (a CAD face's internal edge).
// Glued (scar) they leave the layout as if uncut; free they may open. Either way the domain must be
// valid: two copies of one chain a rounding error apart used to count as crossing boundaries.
#include <cmath>

#include "solve_helpers.hpp"

using namespace wefm;

namespace {

// A gently curved 40 x 40 grid with `k` horizontal slits of 12 facet edges each.
TriMesh slit_plate(int k, std::vector<std::pair<Index, Index>>& seams) {
  const int n = 40;
  TriMesh m = test::grid(n, n, [](double u, double v) { return Vec3(u, v, 0.15 * std::sin(3 * u) * std::cos(2 * v)); });
  auto id = [&](int i, int j) { return static_cast<Index>(j * (n + 1) + i); };
  for (int s = 0; s < k; ++s)
    for (int i = 8; i < 20; ++i) seams.emplace_back(id(i, 4 + 4 * s), id(i + 1, 4 + 4 * s));
  return m;
}

}  // namespace

TEST_CASE("glued slits keep their two sides at one point and never count as crossing boundaries") {
  std::vector<std::pair<Index, Index>> seams;
  const TriMesh m = slit_plate(4, seams);
  const auto r = test::solve(m, test::with_s(0), seams, EdgeMode::Scar);
  Face f;
  f.set_mesh(m);
  f.add_seams(seams);
  const Topology& tp = f.topology();
  REQUIRE(tp.repeated.size() == 4);
  for (const RepeatedEdge& e : tp.repeated)
    for (size_t j = 0; j < e.side_a.size(); ++j) CHECK(r.uv[e.side_a[j]] == r.uv[e.side_b[j]]);
  CHECK(r.report.quality.boundary_intersections == 0);
  CHECK(r.report.quality.flips == 0);
}

TEST_CASE("automatic modes on several slits give a valid layout") {
  for (int k : {2, 4, 8}) {
    CAPTURE(k);
    std::vector<std::pair<Index, Index>> seams;
    const TriMesh m = slit_plate(k, seams);
    const auto r = test::solve(m, test::with_s(0), seams, EdgeMode::Auto);
    MESSAGE(k << " slits: score " << r.report.quality.score << ", factorisations " << r.report.counters.factorizations << ", solves "
              << r.report.counters.solves);
    CHECK(r.report.quality.boundary_intersections == 0);
    CHECK(r.report.quality.flips == 0);
    CHECK(r.report.quality.score > 0.97);
    // Every candidate set of every edge through the one factorisation of the point block.
    CHECK(r.report.counters.factorizations == 1);
  }
}
