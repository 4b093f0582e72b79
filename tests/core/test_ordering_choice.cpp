// The rule between AMD's order and the geometric nested dissection (ordering_choice.hpp), on the
// counts CHOLMOD gave for the benchmark's faces (docs/PERFORMANCE.md): the decisions measured to
// pay are the ones the rule makes.
#include <doctest/doctest.h>

#include "wefm/core/linalg/ordering_choice.hpp"

using namespace wefm;

TEST_CASE("the ordering rule on the counts of the benchmark's faces") {
  SUBCASE("1M disk: AMD's order is poor, the dissection's is not") {
    const double anz = 2.00245e6, n = 500615;
    CHECK(poor_order({4.39727e7, 2.93037e10}, anz));
    CHECK_FALSE(poor_order({2.6955e7, 8.59849e9}, anz));
    CHECK(dissection_acceptable({2.6955e7, 8.59849e9}, anz, n));
  }
  SUBCASE("4M disk: both poor by CHOLMOD's test, the dissection within the planar bound, AMD's order not") {
    const double anz = 8.00005e6, n = 2000015;
    const OrderCounts amd{2.0588e8, 2.27818e11}, nd{1.23696e8, 6.94474e10};
    CHECK(poor_order(amd, anz));
    CHECK(poor_order(nd, anz));  // 561 flops per entry: METIS would have been tried
    CHECK(dissection_acceptable(nd, anz, n));
    CHECK_FALSE(dissection_acceptable(amd, anz, n));  // the same counts from a dissection would not do
  }
  SUBCASE("plates: AMD's order kept outright at 1M, compared at 4M") {
    // 1M: 16.5M entries, 3.7 GFlop (224 per entry); 4M: 421 per entry, the dissection's flops higher.
    CHECK_FALSE(doubtful_order({1.65e7, 3.7e9}, 2.0e6));
    const double anz = 8.0272e6;
    const OrderCounts amd{8.01655e7, 3.38003e10}, nd{1.08547e8, 4.06319e10};
    CHECK_FALSE(poor_order(amd, anz));
    CHECK(doubtful_order(amd, anz));
    CHECK(dissection_acceptable(nd, anz, 2006988));
  }
  SUBCASE("small matrices are never poor or doubtful: few entries per column of K") {
    CHECK_FALSE(poor_order({4.0e4, 1.0e8}, 1.0e4));
    CHECK_FALSE(doubtful_order({4.0e4, 1.0e8}, 1.0e4));
  }
}
