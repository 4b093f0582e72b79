// Points to map that are not numbers or lie far away (wefm_face_map_*): a per-point status for
// each, never a crash, an out-of-bounds read or a silent garbage value.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "capi_meshes.hpp"

using namespace wefm_test;

namespace {

const double kNan = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

}  // namespace

TEST_CASE("map_uv_to_3d: NaN and infinite points get INVALID_ARGUMENT, huge ones OUTSIDE_DOMAIN") {
  Face f(cap(8));
  REQUIRE(wefm_face_solve(f) == WEFM_OK);
  const std::vector<double> uv = get_uv(f);
  // A use's own position, then NaN, +-inf, |u| >= 1.3e154 (where squared distances overflow) and
  // the largest doubles.
  const std::vector<double> q = {uv[0], uv[1], kNan, 0, 0, kInf, -kInf, kNan, 1e154, 0, -1.3e154, 2e154, 1.7976931348623157e308, -1.7976931348623157e308};
  const int64_t n = static_cast<int64_t>(q.size() / 2);
  std::vector<double> xyz(static_cast<size_t>(3 * n));
  std::vector<int32_t> st(static_cast<size_t>(n), -7), tri(static_cast<size_t>(n), -7);
  CHECK(wefm_face_map_uv_to_3d(f, n, q.data(), xyz.data(), st.data(), tri.data()) == WEFM_ERROR_INVALID_ARGUMENT);
  const std::string msg = f.error();
  MESSAGE(msg);
  CHECK(msg.find("3 of 7 points") != std::string::npos);
  CHECK(msg.find("point 1") != std::string::npos);
  CHECK(st[0] == WEFM_OK);
  CHECK(tri[0] >= 0);
  for (int i = 1; i <= 3; ++i) {
    CHECK(st[static_cast<size_t>(i)] == WEFM_ERROR_INVALID_ARGUMENT);
    CHECK(tri[static_cast<size_t>(i)] == -1);
    CHECK(std::isnan(xyz[static_cast<size_t>(3 * i)]));
  }
  for (int i = 4; i < n; ++i) {
    CHECK(st[static_cast<size_t>(i)] == WEFM_ERROR_OUTSIDE_DOMAIN);
    CHECK(tri[static_cast<size_t>(i)] == -1);
    for (int k = 0; k < 3; ++k) CHECK(std::isfinite(xyz[static_cast<size_t>(3 * i + k)]));
    // The cap lies in the unit ball: the image is a point of it.
    CHECK(std::hypot(xyz[static_cast<size_t>(3 * i)], xyz[static_cast<size_t>(3 * i + 1)], xyz[static_cast<size_t>(3 * i + 2)]) <= 1.0 + 1e-9);
  }
  // Finite points alone: OK, and NULL status and triangle arrays are accepted.
  CHECK(wefm_face_map_uv_to_3d(f, 1, q.data() + 8, xyz.data(), nullptr, nullptr) == WEFM_OK);
  CHECK(wefm_face_map_uv_to_3d(f, 1, q.data() + 2, xyz.data(), nullptr, nullptr) == WEFM_ERROR_INVALID_ARGUMENT);
}

TEST_CASE("map_3d_to_uv: NaN and infinite points get INVALID_ARGUMENT, huge ones OUTSIDE_DOMAIN") {
  Face f(cap(8));
  REQUIRE(wefm_face_solve(f) == WEFM_OK);
  const std::vector<double> p = {0, 0, 1, kNan, 0, 0, 0, kInf, 0, 0, 0, -kInf, 1e200, -1e200, 0, 1.7976931348623157e308, 0, -1.7976931348623157e308};
  const int64_t n = static_cast<int64_t>(p.size() / 3);
  std::vector<double> uv(static_cast<size_t>(2 * n));
  std::vector<int32_t> st(static_cast<size_t>(n), -7), tri(static_cast<size_t>(n), -7);
  CHECK(wefm_face_map_3d_to_uv(f, n, p.data(), uv.data(), st.data(), tri.data()) == WEFM_ERROR_INVALID_ARGUMENT);
  MESSAGE(f.error());
  CHECK(st[0] == WEFM_OK);  // the cap's apex
  for (int i = 1; i <= 3; ++i) {
    CHECK(st[static_cast<size_t>(i)] == WEFM_ERROR_INVALID_ARGUMENT);
    CHECK(tri[static_cast<size_t>(i)] == -1);
    CHECK(std::isnan(uv[static_cast<size_t>(2 * i)]));
  }
  for (int i = 4; i < n; ++i) {
    CHECK(st[static_cast<size_t>(i)] == WEFM_ERROR_OUTSIDE_DOMAIN);
    CHECK(std::isfinite(uv[static_cast<size_t>(2 * i)]));
    CHECK(std::isfinite(uv[static_cast<size_t>(2 * i + 1)]));
  }
}

TEST_CASE("far points in every direction map to the domain's boundary") {
  Face f(cap(40));
  REQUIRE(wefm_face_solve(f) == WEFM_OK);
  std::vector<double> q;
  // 500 directions, 0.72 degrees apart: each far point walks the grid's rings to the boundary, the
  // costliest mapping there is, and the sanitizer build runs this test too.
  for (int i = 0; i < 500; ++i) {
    const double a = 2 * 3.141592653589793 * i / 500;
    q.insert(q.end(), {1e100 * std::cos(a), 1e100 * std::sin(a)});
  }
  const int64_t n = static_cast<int64_t>(q.size() / 2);
  std::vector<double> xyz(static_cast<size_t>(3 * n));
  std::vector<int32_t> st(static_cast<size_t>(n));
  CHECK(wefm_face_map_uv_to_3d(f, n, q.data(), xyz.data(), st.data(), nullptr) == WEFM_OK);
  for (int32_t s : st) CHECK(s == WEFM_ERROR_OUTSIDE_DOMAIN);
  CHECK(all_finite(xyz));
}
