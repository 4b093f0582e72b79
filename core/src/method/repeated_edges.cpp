#include "wefm/core/method/repeated_edges.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace wefm {

namespace {

LinearRow make_row(std::initializer_list<std::pair<Index, Complex>> terms) {
  std::map<Index, Complex> acc;
  for (auto& [u, g] : terms) acc[u] += g;
  LinearRow r;
  for (auto& [u, g] : acc)
    if (std::abs(g) > 1e-14) r.terms.emplace_back(u, g);
  return r;
}

}  // namespace

std::vector<LinearRow> repeated_edge_rows(const RepeatedEdge& e, EdgeMode mode, Complex w) {
  std::vector<LinearRow> rows;
  const size_t m = e.side_a.size();
  if (mode == EdgeMode::Scar) {
    for (size_t j = 0; j < m; ++j) {
      LinearRow r = make_row({{e.side_a[j], 1.0}, {e.side_b[j], -1.0}});
      if (!r.terms.empty()) rows.push_back(std::move(r));
    }
  } else if (mode == EdgeMode::Periodic || mode == EdgeMode::Rotational) {
    if (mode == EdgeMode::Periodic) w = 1.0;
    // (z_aj - w z_bj) - (z_a0 - w z_b0) = 0: side a is side b moved by one rigid motion.
    for (size_t j = 1; j < m; ++j) {
      LinearRow r = make_row({{e.side_a[j], 1.0}, {e.side_b[j], -w}, {e.side_a[0], -1.0}, {e.side_b[0], w}});
      if (!r.terms.empty()) rows.push_back(std::move(r));
    }
  }
  return rows;
}

Complex estimate_rotation(const RepeatedEdge& e, const VectorXc& z) {
  Complex acc{0, 0};
  for (size_t j = 0; j + 1 < e.side_a.size(); ++j) {
    const Complex da = z[e.side_a[j + 1]] - z[e.side_a[j]], db = z[e.side_b[j + 1]] - z[e.side_b[j]];
    acc += da * std::conj(db);
  }
  const double r = std::abs(acc);
  return r > 0 ? acc / r : Complex(1, 0);
}

bool sides_coincide(const RepeatedEdge& e, const VectorXc& z) {
  double extent = 0, gap = 0;
  for (size_t j = 0; j < e.side_a.size(); ++j) {
    extent = std::max(extent, std::abs(z[e.side_a[j]] - z[e.side_a[0]]));
    gap = std::max(gap, std::abs(z[e.side_a[j]] - z[e.side_b[j]]));
  }
  return gap <= 1e-6 * extent;
}

void glue_scars(const Topology& tp, const std::vector<EdgeMode>& modes, VectorXc& z) {
  for (const RepeatedEdge& r : tp.repeated) {
    if (modes[static_cast<size_t>(r.edge)] != EdgeMode::Scar) continue;
    for (size_t j = 0; j < r.side_a.size(); ++j) z[r.side_b[j]] = z[r.side_a[j]];
  }
}

}  // namespace wefm
