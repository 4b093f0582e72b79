// ModelMesh (apps/wefm/model_mesh.hpp), the welded whole-model mesh, as a unit: the two halves of
// a quad are split along its better diagonal, so a quad with a corner near 180 degrees is not
// reported as a zero-area triangle, while a triangle mesh's own sliver still is.
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
