#pragma once
#include <doctest/doctest.h>

#include "meshes.hpp"
#include "wefm/core/sys/error.hpp"
#include "wefm/core/solve/face.hpp"
#include "wefm/core/mesh/mesh_io.hpp"

namespace wefm::test {

inline FlattenResult solve(const TriMesh& m, Options o, const std::vector<std::pair<Index, Index>>& seams = {}, EdgeMode mode = EdgeMode::Auto) {
  Face f;
  f.set_mesh(m);
  o.default_edge_mode = mode;
  f.set_options(o);
  if (!seams.empty()) f.add_seams(seams);
  f.solve(nullptr, nullptr);
  return f.result();
}

// Solves a face whose continuation may end on its iteration cap: NOT_CONVERGED keeps the layout
// reached, and the test asserts its properties either way; any other error fails the test.
inline const FlattenResult& solve_allowing_cap(Face& f) {
  try {
    f.solve(nullptr, nullptr);
  } catch (const Error& e) {
    CHECK(e.code() == Errc::not_converged);
  }
  REQUIRE(f.has_result());
  return f.result();
}

inline Options with_s(double s, double mu = 1.0) {
  Options o;
  o.s = s;
  o.max_rho_iterations = 60;
  o.boundary_weight = mu;
  return o;
}

}  // namespace wefm::test
