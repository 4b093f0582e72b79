#include "cad_edge_nodes.hpp"

#include <algorithm>
#include <cmath>

namespace wefm_cad {

namespace {

double distance(const double* a, const double* b) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

EdgeNodes resample(const CadFace& face, const CadEdge& edge, double h) {
  const size_t m = edge.vertices.size();
  std::vector<const double*> p(m);
  for (size_t i = 0; i < m; ++i) p[i] = &face.xyz[3 * static_cast<size_t>(edge.vertices[i])];
  std::vector<double> s(m, 0.0);  // arc length at each chain vertex
  for (size_t i = 1; i < m; ++i) s[i] = s[i - 1] + distance(p[i - 1], p[i]);
  const bool closed = edge.vertices.front() == edge.vertices.back();
  const long long n = std::max<long long>(closed ? 3 : 1, std::llround(s.back() / h));
  EdgeNodes out;
  out.xyz.insert(out.xyz.end(), p[0], p[0] + 3);
  size_t seg = 1;
  for (long long k = 1; k < n; ++k) {
    const double target = s.back() * static_cast<double>(k) / static_cast<double>(n);
    while (seg + 1 < m && s[seg] < target) ++seg;
    const double len = s[seg] - s[seg - 1];
    const double t = len > 0 ? std::clamp((target - s[seg - 1]) / len, 0.0, 1.0) : 0.0;
    for (int c = 0; c < 3; ++c) out.xyz.push_back(p[seg - 1][c] + t * (p[seg][c] - p[seg - 1][c]));
  }
  out.xyz.insert(out.xyz.end(), p[m - 1], p[m - 1] + 3);
  return out;
}

}  // namespace

std::map<long long, EdgeNodes> discretise_model_edges(const CadModel& model, double h) {
  std::map<long long, EdgeNodes> nodes;
  for (const CadFace& f : model.faces) {
    if (!f.error.empty()) continue;
    for (const CadEdge& e : f.edges)
      if (!e.degenerated && e.vertices.size() >= 2 && !nodes.count(e.id)) nodes.emplace(e.id, resample(f, e, h));
  }
  return nodes;
}

}  // namespace wefm_cad
