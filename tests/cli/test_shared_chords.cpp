// faces_with_shared_chords (apps/wefm/shared_chords.hpp) as a unit: a face whose mesh joins two of
// its boundary nodes by an edge inside it that another face's mesh also has is found; a face lying
// on the other (meshed alike on purpose) and a face with no such chord are not.
#include <doctest/doctest.h>

#include <vector>

#include "shared_chords.hpp"

using wefm_cli::FaceMeshView;
using wefm_cli::faces_with_shared_chords;

namespace {

// Two faces as their meshes might be (only nodes and edges matter): two triangles each, both joined
// along p = (0,0,0) - q = (2,0,0), an edge inside each face between two of its boundary nodes.
const std::vector<double> kUpper = {0, 0, 0, 1, 1, 0, 2, 0, 0, 1, 0, 1};   // p, a, q, b
const std::vector<int32_t> kUpperTris = {0, 1, 2, 0, 2, 3};                 // chord p-q inside
const std::vector<double> kLower = {0, 0, 0, 1, -1, 0, 2, 0, 0, 1, 0, -1};  // p, c, q, d
const std::vector<int32_t> kLowerTris = {0, 2, 1, 0, 3, 2};                 // chord p-q inside
// A face with p-q on its boundary and no chord: one triangle.
const std::vector<double> kFlap = {0, 0, 0, 2, 0, 0, 1, 0, 5};
const std::vector<int32_t> kFlapTris = {0, 1, 2};
// A face with no node at q: shares only p.
const std::vector<double> kApart = {0, 0, 0, -1, 1, 0, -1, -1, 0};
const std::vector<int32_t> kApartTris = {0, 1, 2};

}  // namespace

TEST_CASE("faces that join the same two boundary nodes by a chord inside them are found") {
  const std::vector<FaceMeshView> faces = {{&kUpper, &kUpperTris}, {&kLower, &kLowerTris}, {&kApart, &kApartTris}};
  CHECK(faces_with_shared_chords(faces, {0, 0, 0}, 1e-9) == std::vector<size_t>{0, 1});
}

TEST_CASE("a chord that is another face's boundary segment is found in the face with the chord only") {
  const std::vector<FaceMeshView> faces = {{&kFlap, &kFlapTris}, {&kUpper, &kUpperTris}};
  CHECK(faces_with_shared_chords(faces, {0, 0}, 1e-9) == std::vector<size_t>{1});
}

TEST_CASE("faces lying on each other, or on one face, share their chords on purpose") {
  const std::vector<FaceMeshView> two = {{&kUpper, &kUpperTris}, {&kLower, &kLowerTris}};
  CHECK(faces_with_shared_chords(two, {0, 1}, 1e-9).empty());  // 1 lies on 0
  const std::vector<FaceMeshView> three = {{&kUpper, &kUpperTris}, {&kLower, &kLowerTris}, {&kUpper, &kUpperTris}};
  CHECK(faces_with_shared_chords(three, {3, 3, 0}, 1e-9).empty());  // 0 and 1 both lie on 2
  // 1 lies on 0, but the flap lies on neither: its segment p-q is the chord of both.
  const std::vector<FaceMeshView> flap = {{&kUpper, &kUpperTris}, {&kLower, &kLowerTris}, {&kFlap, &kFlapTris}};
  CHECK(faces_with_shared_chords(flap, {0, 1, 0}, 1e-9) == std::vector<size_t>{0, 1});
}

TEST_CASE("nodes within the tolerance match, farther ones do not") {
  std::vector<double> lower = kLower;
  lower[6] += 1e-12;  // q, well within
  const std::vector<FaceMeshView> near = {{&kUpper, &kUpperTris}, {&lower, &kLowerTris}};
  CHECK(faces_with_shared_chords(near, {0, 0}, 1e-9).size() == 2);
  lower[6] += 1e-3;  // q moved apart
  const std::vector<FaceMeshView> far = {{&kUpper, &kUpperTris}, {&lower, &kLowerTris}};
  CHECK(faces_with_shared_chords(far, {0, 0}, 1e-9).empty());
}
