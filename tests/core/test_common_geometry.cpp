// lo_lambda and LinearSize (common/include/wefm/common/): the triangle quality and the graded node
// spacing that the library's mesher and the tool's model edges share.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "wefm/common/linear_size.hpp"
#include "wefm/common/lo_lambda.hpp"

namespace {

double lambda(std::vector<double> a, std::vector<double> b, std::vector<double> c) {
  return wefm_common::lo_lambda(a.data(), b.data(), c.data());
}

}  // namespace

TEST_CASE("lo_lambda: 1 for an equilateral triangle in any position, 0 without area") {
  const double r = std::sqrt(3.0) / 2;
  CHECK(lambda({0, 0, 0}, {1, 0, 0}, {0.5, r, 0}) == doctest::Approx(1.0).epsilon(1e-14));
  // Rotated out of plane, moved and scaled: still 1.
  CHECK(lambda({5, 5, 5}, {5, 5 + 3, 5}, {5, 5 + 1.5, 5 + 3 * r}) == doctest::Approx(1.0).epsilon(1e-14));
  CHECK(lambda({0, 0, 0}, {1, 0, 0}, {2, 0, 0}) == 0.0);  // collinear
  CHECK(lambda({1, 2, 3}, {1, 2, 3}, {1, 2, 3}) == 0.0);  // one point: no division by zero
}

TEST_CASE("lo_lambda: a right isosceles triangle is sqrt(3)/2, and order and orientation do not matter") {
  const double x = lambda({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  CHECK(x == doctest::Approx(std::sqrt(3.0) / 2).epsilon(1e-14));  // 4 sqrt(3) (1/2) / (1 + 1 + 2)
  CHECK(lambda({0, 1, 0}, {1, 0, 0}, {0, 0, 0}) == doctest::Approx(x).epsilon(1e-15));
  CHECK(lambda({1, 0, 0}, {0, 1, 0}, {0, 0, 0}) == doctest::Approx(x).epsilon(1e-15));
  // A needle: long and thin is far below 1.
  CHECK(lambda({0, 0, 0}, {10, 0, 0}, {5, 0.1, 0}) < 0.05);
}

TEST_CASE("LinearSize: a constant size spaces nodes evenly, a linear one by its integral") {
  wefm_common::LinearSize even;
  even.append(0, 10, 2, 0);
  CHECK(even.total() == doctest::Approx(5.0));
  for (int k = 0; k <= 5; ++k) CHECK(even.inverse(k) == doctest::Approx(2.0 * k));

  // size(s) = 1 + s on [0, 3]: the integral is log(1 + s); node k of n at exp(k total / n) - 1.
  wefm_common::LinearSize rising;
  rising.append(0, 3, 1, 1);
  CHECK(rising.total() == doctest::Approx(std::log(4.0)));
  for (int k = 0; k <= 4; ++k) {
    const double phi = rising.total() * k / 4;
    CHECK(rising.inverse(phi) == doctest::Approx(std::exp(phi) - 1));
  }
  // Each segment is longer than the one before, as the size grows.
  double last = 0, prev = 0;
  for (int k = 1; k <= 4; ++k) {
    const double s = rising.inverse(rising.total() * k / 4);
    CHECK(s - prev > last);
    last = s - prev, prev = s;
  }
}

TEST_CASE("LinearSize: pieces join, and values past either end stay on the curve") {
  wefm_common::LinearSize two;
  two.append(0, 2, 1, 0);      // 2 segments of 1
  two.append(2, 6, 1, 0.5);    // size 1 + (s - 2) / 2: integral 2 log(3)
  CHECK(two.total() == doctest::Approx(2 + 2 * std::log(3.0)));
  CHECK(two.inverse(2.0) == doctest::Approx(2.0));
  CHECK(two.inverse(two.total()) == doctest::Approx(6.0));
  CHECK(two.inverse(-1.0) == 0.0);
  CHECK(two.inverse(two.total() + 5) == 6.0);
  // Inverse is monotone.
  double prev = -1;
  for (int k = 0; k <= 50; ++k) {
    const double s = two.inverse(two.total() * k / 50);
    CHECK(s >= prev);
    prev = s;
  }
}
