#include "wefm/core/method/caller_rows.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "wefm/core/sys/error.hpp"

namespace wefm {

std::vector<LinearRow> normalised_caller_rows(const std::vector<LinearRow>& rows, double length_scale) {
  std::vector<LinearRow> out = rows;
  for (size_t k = 0; k < out.size(); ++k) {
    LinearRow& r = out[k];
    double big = 0;
    for (const auto& t : r.terms) big = std::max({big, std::abs(t.second.real()), std::abs(t.second.imag())});
    if (big == 0) {
      if (r.rhs != Complex(0, 0))
        fail(Errc::invalid_constraint, "constraint " + std::to_string(k) + " has only zero coefficients but a non-zero right-hand side: it can never hold");
      continue;  // 0 = 0: says nothing; the KKT system reports it as a redundant row if it matters
    }
    // Divided in two steps: rhs / (big * ls) can overflow where each quotient does not.
    const Complex rhs = r.rhs / length_scale / big;
    const double reach = std::max(std::abs(rhs.real()), std::abs(rhs.imag()));
    if (!(reach <= kMaxConstraintReach))
      fail(Errc::invalid_constraint,
           "constraint " + std::to_string(k) + " places the layout about " + (std::isfinite(reach) ? message_number(reach) : std::string("infinitely many")) +
               " mean edge lengths (" + message_number(length_scale) + " each) from the origin: its right-hand side over its largest coefficient may be at most " +
               message_number(kMaxConstraintReach) + " edge lengths, beyond which double precision cannot resolve the face's triangles");
    for (auto& t : r.terms) t.second /= big;
    r.rhs = rhs;
  }
  return out;
}

}  // namespace wefm
