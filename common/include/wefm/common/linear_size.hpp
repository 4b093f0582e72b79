#pragma once
// Node spacing along a curve whose element size is linear on each piece of its arc length: nodes
// sit at equal steps of the integral of 1 / size, which is closed-form on a linear piece (a log,
// and its inverse an exp). Written once for the library's boundary grading (core/meshing/
// graded_spacing) and the tool's model edges (apps/cad/cad_edge_nodes), which must space the
// nodes of an edge alike on both sides of the C API.
#include <algorithm>
#include <cmath>
#include <vector>

namespace wefm_common {

class LinearSize {
 public:
  // Appends the piece [a, b] (b > a, starting where the last ended) on which the size is
  // c0 + c1 (s - a), positive over the piece.
  void append(double a, double b, double c0, double c1) {
    const Piece p{a, b, total_, c0, c1};
    total_ += p.integral(b);
    pieces_.push_back(p);
  }
  bool empty() const { return pieces_.empty(); }
  // The integral of 1 / size over all pieces: about the number of segments the size asks for.
  double total() const { return total_; }
  // The arc length at which the integral reaches `phi`, within the pieces (clamped to them).
  // Needs a piece.
  double inverse(double phi) const {
    for (const Piece& p : pieces_) {
      const double span = p.integral(p.b);
      if (phi <= p.phi0 + span || &p == &pieces_.back()) {
        const double t = std::clamp(phi - p.phi0, 0.0, span);
        const double s = p.c1 == 0 ? p.a + p.c0 * t : p.a + p.c0 * (std::exp(p.c1 * t) - 1) / p.c1;
        return std::clamp(s, p.a, p.b);
      }
    }
    return 0;
  }

 private:
  struct Piece {
    double a, b, phi0, c0, c1;
    double integral(double s) const { return c1 == 0 ? (s - a) / c0 : std::log((c0 + c1 * (s - a)) / c0) / c1; }
  };
  std::vector<Piece> pieces_;
  double total_ = 0;
};

}  // namespace wefm_common
