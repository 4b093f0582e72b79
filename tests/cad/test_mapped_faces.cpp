// Mapped meshing planned for a whole model (apps/wefm/mapped_faces.hpp), as a unit on faces built
// by hand: which faces are four-sided by their corners, and how the segment counts of opposite sides
// are matched across faces that share edges (counts only grow, at most doubled; a face that cannot
// be matched stays free and the others keep their counts), the recounted edges graded as before.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "cad_edge_nodes.hpp"
#include "mapped_faces.hpp"

using wefm_cad::CadFace;
using wefm_cad::CadModel;
using wefm_cli::FourSides;

namespace {

using Point = std::array<double, 2>;

// A planar face in z = 0 with the polygon's corners counter-clockwise (the face on the left, its
// normal +z), fanned from its centroid; edge k runs from corner k to corner k + 1 with model id
// ids[k] (a negative id: the edge is model edge -id walked backwards, as a neighbour shares it).
CadFace polygon_face(int index, const std::vector<Point>& corners, const std::vector<long long>& ids) {
  CadFace f;
  f.index = index;
  f.surface_type = "plane";
  const size_t n = corners.size();
  double cx = 0, cy = 0;
  for (const Point& p : corners) {
    f.xyz.insert(f.xyz.end(), {p[0], p[1], 0});
    cx += p[0] / static_cast<double>(n), cy += p[1] / static_cast<double>(n);
  }
  f.xyz.insert(f.xyz.end(), {cx, cy, 0});
  std::vector<wefm_cad::CadEdgeUse> loop;
  for (size_t k = 0; k < n; ++k) {
    const auto a = static_cast<int32_t>(k), b = static_cast<int32_t>((k + 1) % n);
    f.triangles.insert(f.triangles.end(), {a, b, static_cast<int32_t>(n)});
    wefm_cad::CadEdge e;
    e.id = std::llabs(ids[k]);
    e.vertices = ids[k] > 0 ? std::vector<int32_t>{a, b} : std::vector<int32_t>{b, a};
    e.curve_type = "Line";
    f.edges.push_back(e);
    loop.push_back({static_cast<int32_t>(k), ids[k] < 0});
  }
  f.loops.push_back(loop);
  f.outer_loop = 0;
  return f;
}

CadModel model_of(std::vector<CadFace> faces) {
  CadModel m;
  m.faces = std::move(faces);
  m.bbox_diagonal = 5;
  return m;
}

long long segments(const std::map<long long, wefm_cad::EdgeNodes>& nodes, long long id) {
  return static_cast<long long>(nodes.at(id).xyz.size() / 3) - 1;
}

// A trapezoid: bottom (edge 1) 3 long, top (edge 3) 2 long, slanted sides (2, 4) about 1.1.
const std::vector<Point> kTrapezoid = {{0, 0}, {3, 0}, {2.5, 1}, {0.5, 1}};

}  // namespace

TEST_CASE("four sides: corners between 30 and 150 degrees; smooth joins inside a side; holes, poles and five corners are not") {
  FourSides s;
  std::string why;
  CHECK(wefm_cli::four_sides(polygon_face(1, kTrapezoid, {1, 2, 3, 4}), s, why));
  CHECK(s.edges[0].size() + s.edges[1].size() + s.edges[2].size() + s.edges[3].size() == 4);
  // A rectangle whose bottom is two edges in line: four sides, one of them two edges long.
  const CadFace split = polygon_face(1, {{0, 0}, {1, 0}, {2, 0}, {2, 1}, {0, 1}}, {1, 2, 3, 4, 5});
  REQUIRE(wefm_cli::four_sides(split, s, why));
  size_t two = 0, at = 0;
  for (size_t k = 0; k < 4; ++k)
    if (s.edges[k].size() == 2) ++two, at = k;
  CHECK(two == 1);
  CHECK(s.length[at] == doctest::Approx(2));
  CHECK(s.length[(at + 2) % 4] == doctest::Approx(2));
  CHECK(s.length[(at + 1) % 4] == doctest::Approx(1));
  // A pentagon (every corner 108 degrees).
  std::vector<Point> penta;
  for (int k = 0; k < 5; ++k) penta.push_back({std::cos(2 * 3.14159265358979 * k / 5), std::sin(2 * 3.14159265358979 * k / 5)});
  CHECK_FALSE(wefm_cli::four_sides(polygon_face(1, penta, {1, 2, 3, 4, 5}), s, why));
  CHECK(why == "5 corners");
  // A sharp corner (about 11 degrees) is not a grid's corner.
  CHECK_FALSE(wefm_cli::four_sides(polygon_face(1, {{0, 0}, {5, 0}, {5, 1}, {4, 1}}, {1, 2, 3, 4}), s, why));
  CHECK(why.find("a corner of") == 0);
  // Opposite sides 4 and 1 long.
  CHECK_FALSE(wefm_cli::four_sides(polygon_face(1, {{0, 0}, {4, 0}, {2.5, 1}, {1.5, 1}}, {1, 2, 3, 4}), s, why));
  CHECK(why == "opposite sides of unlike lengths");
  CadFace holed = polygon_face(1, kTrapezoid, {1, 2, 3, 4});
  holed.loops.push_back(holed.loops[0]);
  CHECK_FALSE(wefm_cli::four_sides(holed, s, why));
  CHECK(why == "holes");
}

TEST_CASE("a trapezoid's short side gets as many segments as the long one, the others keep theirs") {
  const CadModel model = model_of({polygon_face(1, kTrapezoid, {1, 2, 3, 4})});
  auto nodes = wefm_cad::discretise_model_edges(model, 1.0);
  REQUIRE(segments(nodes, 1) == 3);
  REQUIRE(segments(nodes, 3) == 2);
  const auto m = wefm_cli::map_four_sided_faces(model, {}, true, {}, {}, nodes);
  CHECK(m.faces.count(0) == 1);
  CHECK(m.four_sided == 1);
  CHECK(segments(nodes, 3) == 3);
  CHECK(segments(nodes, 1) == 3);
  CHECK(segments(nodes, 2) == segments(nodes, 4));
  CHECK(m.recounted == std::set<long long>{3});
  // Not asked for: nothing mapped, nothing recounted.
  auto same = wefm_cad::discretise_model_edges(model, 1.0);
  const auto none = wefm_cli::map_four_sided_faces(model, {}, false, {}, {}, same);
  CHECK(none.faces.empty());
  CHECK(segments(same, 3) == 2);
}

TEST_CASE("counts are matched across faces: an edge one face makes finer makes its neighbour's opposite side finer") {
  // The trapezoid, and on its top edge (3, walked backwards) a 2 x 1 rectangle whose top (edge 7) has
  // two segments: matching the trapezoid gives edge 3 three, and the rectangle's top must follow.
  const CadModel model = model_of({polygon_face(1, kTrapezoid, {1, 2, 3, 4}),
                                   polygon_face(2, {{0.5, 1}, {2.5, 1}, {2.5, 2}, {0.5, 2}}, {-3, 6, 7, 8})});
  auto nodes = wefm_cad::discretise_model_edges(model, 1.0);
  REQUIRE(segments(nodes, 7) == 2);
  const auto m = wefm_cli::map_four_sided_faces(model, {}, true, {}, {}, nodes);
  CHECK(m.faces.size() == 2);
  CHECK(segments(nodes, 1) == segments(nodes, 3));
  CHECK(segments(nodes, 3) == segments(nodes, 7));
  CHECK(segments(nodes, 2) == segments(nodes, 4));
  CHECK(segments(nodes, 6) == segments(nodes, 8));
  CHECK(segments(nodes, 7) == 3);
  CHECK(wefm_cli::mismatched_faces(m, nodes) == 0);
  // A node added to an edge afterwards (a neighbour's kink) unmatches the faces on it.
  auto& top = nodes.at(7).xyz;
  top.insert(top.end() - 3, {1.0, 2.0, 0.0});
  CHECK(wefm_cli::mismatched_faces(m, nodes) == 1);
}

TEST_CASE("a face whose counts cannot be matched within the growth stays free; faces fixed before keep their edges") {
  // Bottom 2.9 long (3 segments), top 1 (1 segment): the top would have to triple.
  const CadModel model = model_of({polygon_face(1, {{0, 0}, {2.9, 0}, {1.95, 1}, {0.95, 1}}, {1, 2, 3, 4})});
  auto nodes = wefm_cad::discretise_model_edges(model, 1.0);
  REQUIRE(segments(nodes, 1) == 3);
  REQUIRE(segments(nodes, 3) == 1);
  const auto m = wefm_cli::map_four_sided_faces(model, {}, true, {}, {}, nodes);
  CHECK(m.faces.empty());
  CHECK(m.four_sided == 1);
  CHECK(m.refused.count(0) == 1);
  CHECK(segments(nodes, 3) == 1);
  CHECK(m.recounted.empty());
  // The trapezoid with its edges fixed (a mapped tube's, say): not mapped, its top left at two.
  const CadModel trap = model_of({polygon_face(1, kTrapezoid, {1, 2, 3, 4}), polygon_face(2, kTrapezoid, {11, 12, 13, 14})});
  auto tn = wefm_cad::discretise_model_edges(trap, 1.0);
  const auto fixed = wefm_cli::map_four_sided_faces(trap, {}, true, {0}, {}, tn);
  CHECK(fixed.faces == std::set<size_t>{1});
  CHECK(segments(tn, 3) == 2);
  CHECK(segments(tn, 13) == 3);
}

TEST_CASE("a face named by the caller is meshed mapped even when it is not four-sided, with the reason noted") {
  std::vector<Point> penta;
  for (int k = 0; k < 5; ++k) penta.push_back({std::cos(2 * 3.14159265358979 * k / 5), std::sin(2 * 3.14159265358979 * k / 5)});
  const CadModel model = model_of({polygon_face(1, penta, {1, 2, 3, 4, 5})});
  auto nodes = wefm_cad::discretise_model_edges(model, 0.5);
  const auto m = wefm_cli::map_four_sided_faces(model, {0}, false, {}, {}, nodes);
  CHECK(m.faces.count(0) == 1);
  CHECK(m.refused.at(0).find("not four-sided") == 0);
}

TEST_CASE("recounted edge nodes keep their grading: the end with the short segments keeps the short ones") {
  const CadModel model = model_of({polygon_face(1, {{0, 0}, {10, 0}, {10, 1}, {0, 1}}, {1, 2, 3, 4})});
  const CadFace& f = model.faces[0];
  wefm_cad::EdgeNodes graded;
  for (double x : {0.0, 0.25, 0.75, 1.75, 3.5, 6.5, 10.0}) graded.xyz.insert(graded.xyz.end(), {x, 0, 0});
  const auto more = wefm_cad::recount_edge_nodes(f, f.edges[0], graded, 9);
  REQUIRE(more.xyz.size() == 30);
  CHECK(more.xyz[0] == 0);
  CHECK(more.xyz[27] == doctest::Approx(10));
  for (size_t k = 1; k < 10; ++k) CHECK(more.xyz[3 * k] > more.xyz[3 * (k - 1)]);
  const double first = more.xyz[3], last = 10 - more.xyz[24];
  CHECK(first < 0.25);
  CHECK(last > 5 * first);
}
