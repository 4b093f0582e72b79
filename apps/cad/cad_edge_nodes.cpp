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

double chain_length(const CadFace& f, const CadEdge& e) {
  double length = 0;
  for (size_t i = 0; i + 1 < e.vertices.size(); ++i)
    length += distance(&f.xyz[3 * static_cast<size_t>(e.vertices[i])], &f.xyz[3 * static_cast<size_t>(e.vertices[i + 1])]);
  return length;
}

std::vector<double> local_face_sizes(const CadModel& model, double h) {
  std::vector<double> sizes(model.faces.size(), h);
  for (size_t k = 0; k < model.faces.size(); ++k) {
    const CadFace& f = model.faces[k];
    if (!f.error.empty()) continue;
    double area = 0;
    for (size_t t = 0; t + 2 < f.triangles.size(); t += 3) {
      const double* a = &f.xyz[3 * static_cast<size_t>(f.triangles[t])];
      const double* b = &f.xyz[3 * static_cast<size_t>(f.triangles[t + 1])];
      const double* c = &f.xyz[3 * static_cast<size_t>(f.triangles[t + 2])];
      const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
      const double x = u[1] * v[2] - u[2] * v[1], y = u[2] * v[0] - u[0] * v[2], z = u[0] * v[1] - u[1] * v[0];
      area += 0.5 * std::sqrt(x * x + y * y + z * z);
    }
    double perimeter = 0;  // over the loops: a seam counts twice, as it bounds the domain twice
    for (const auto& loop : f.loops)
      for (const CadEdgeUse& u : loop) perimeter += chain_length(f, f.edges[static_cast<size_t>(u.edge)]);
    if (perimeter > 0) sizes[k] = std::clamp(2 * area / perimeter, h / 4, h);
  }
  return sizes;
}

std::map<long long, EdgeNodes> discretise_model_edges(const CadModel& model, double h, const std::vector<double>& face_sizes) {
  std::map<long long, double> edge_size;
  for (size_t k = 0; k < model.faces.size(); ++k) {
    const double hf = k < face_sizes.size() ? face_sizes[k] : h;
    for (const CadEdge& e : model.faces[k].edges) {
      auto [it, fresh] = edge_size.emplace(e.id, hf);
      if (!fresh) it->second = std::min(it->second, hf);
    }
  }
  std::map<long long, EdgeNodes> nodes;
  for (const CadFace& f : model.faces) {
    if (!f.error.empty()) continue;
    for (const CadEdge& e : f.edges)
      if (!e.degenerated && e.vertices.size() >= 2 && !nodes.count(e.id)) nodes.emplace(e.id, resample(f, e, edge_size.at(e.id)));
  }
  return nodes;
}

}  // namespace wefm_cad
