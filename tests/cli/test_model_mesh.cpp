// ModelMesh (apps/wefm/model_mesh.hpp), the welded whole-model mesh, as a unit: the two halves of
// a quad are split along its better diagonal, so a quad with a corner near 180 degrees is not
// reported as a zero-area triangle, while a triangle mesh's own sliver still is; a fin closing a
// model vertex's corner goes with the vertex, and the chord it leaves is checked; a model-edge
// segment no triangle uses names the faces at its ends.
#include <doctest/doctest.h>

#include <vector>

#include "model_mesh.hpp"

using wefm_cli::ModelMesh;

namespace {

// A convex quad a, b, c, d (counter-clockwise) whose corner at b is 180 degrees less 1e-7 radians
// and whose shorter diagonal is a-c: the half a, b, c has no area to speak of (Lo lambda about 1e-7).
const std::vector<double> kCorners = {0, 0, 0, 1, -1e-7, 0, 2, 0, 0, 1, 3, 0};
const std::vector<int32_t> kShorterDiagonal = {0, 1, 2, 0, 2, 3};

}  // namespace

TEST_CASE("a quad's halves are split along its better diagonal: no zero-area triangle, one quad") {
  ModelMesh mesh(1e-9);
  CHECK(mesh.add_face(1, kCorners, kShorterDiagonal, {}, {0, 0}) == 0);
  const auto c = mesh.conformity();
  CHECK(c.zero_area_triangles == 0);
  CHECK(c.open_edges == 4);
  CHECK(mesh.quads().quads == 1);
  CHECK(mesh.quads().area_fraction == doctest::Approx(1.0));
  CHECK(mesh.lambda().lambda_min > 0.3);
}

TEST_CASE("the same two triangles not from one quad are left as they are, and the sliver is a defect") {
  ModelMesh mesh(1e-9);
  mesh.add_face(1, kCorners, kShorterDiagonal);
  CHECK(mesh.conformity().zero_area_triangles == 1);
  CHECK(mesh.quads().quads == 0);
}

namespace {

// Two faces that close the corner at model vertex V (between model edges V-A and V-B) with the same
// triangle, once each way: a wall V, A, X, B and a face folded round its corner (a narrow step merged
// into its floor) V, B, A plus B, Y, A. V is on nothing else.
const std::vector<double> kWall = {0, 0, 0, 1, 0, 0, 0, 0, 1, 1, 0, 1};          // V, A, B, X
const std::vector<double> kFolded = {0, 0, 0, 1, 0, 0, 0, 0, 1, 0.5, 1, 0.5};    // V, A, B, Y
const std::vector<double> kVA = {0, 0, 0, 1, 0, 0}, kVB = {0, 0, 0, 0, 0, 1};
const std::vector<double> kAXB = {1, 0, 0, 1, 0, 1, 0, 0, 1}, kBYA = {0, 0, 1, 0.5, 1, 0.5, 1, 0, 0};

}  // namespace

TEST_CASE("a fin closing a model vertex's corner is dropped with the vertex, the chord left checked like any edge") {
  ModelMesh mesh(1e-9);
  mesh.add_face(1, kWall, {0, 1, 2, 1, 3, 2});
  mesh.add_face(2, kFolded, {0, 2, 1, 2, 3, 1});
  CHECK(mesh.drop_fins({}) == 2);
  for (const auto* edge : {&kVA, &kVB}) mesh.expect_model_edge(*edge, 2);
  for (const auto* edge : {&kAXB, &kBYA}) mesh.expect_model_edge(*edge, 1);  // free edges of the two
  const auto c = mesh.conformity();
  CHECK(c.unexplained_open_edges == 0);
  CHECK(c.unexplained_non_manifold_edges == 0);
  CHECK(c.open_edges == 4);
  CHECK(c.non_manifold_edges == 0);
}

TEST_CASE("with the fin dropped, a chord that only one triangle uses is still a gap") {
  ModelMesh mesh(1e-9);
  mesh.add_face(1, kWall, {0, 1, 2, 1, 3, 2});
  mesh.add_face(2, std::vector<double>(kFolded.begin(), kFolded.begin() + 9), {0, 2, 1});
  // The folded face is only the fin's triangle: V and its two model edges go, and A-B is left open.
  CHECK(mesh.drop_fins({}) == 2);
  for (const auto* edge : {&kVA, &kVB}) mesh.expect_model_edge(*edge, 2);
  mesh.expect_model_edge(kAXB, 1);
  CHECK(mesh.conformity().unexplained_open_edges == 1);
}

TEST_CASE("a model-edge segment no triangle uses is a gap, and the faces at its ends are named") {
  // A square split along a-c; a model edge said to run b-d, the other diagonal, which no triangle has
  // (a face that lost its side of an edge, as a cone's apex lost by welding).
  ModelMesh mesh(1e-9);
  const std::vector<double> square = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};  // a, b, c, d
  mesh.add_face(7, square, {0, 1, 2, 0, 2, 3});
  for (int k = 0; k < 4; ++k)  // its sides are free edges
    mesh.expect_model_edge({square[3 * k], square[3 * k + 1], 0, square[3 * ((k + 1) % 4)], square[3 * ((k + 1) % 4) + 1], 0}, 1);
  mesh.expect_model_edge({1, 0, 0, 0, 1, 0}, 2);
  const auto c = mesh.conformity();
  CHECK(c.unexplained_open_edges == 1);
  REQUIRE(c.defect_edges.size() == 1);
  CHECK(c.defect_edges[0].uses == 0);
  CHECK(c.defect_faces == std::vector<int>{7});
}
