#include "face_corners.hpp"

#include <algorithm>
#include <cmath>
#include <map>

namespace wefm_cli {

namespace {

const double* at(const wefm_cad::CadFace& f, int32_t v) { return &f.xyz[3 * static_cast<size_t>(v)]; }

// An edge use's chain of face vertices in the loop's direction.
std::vector<int32_t> chain(const wefm_cad::CadFace& f, const wefm_cad::CadEdgeUse& u) {
  std::vector<int32_t> c = f.edges[static_cast<size_t>(u.edge)].vertices;
  if (u.reversed) std::reverse(c.begin(), c.end());
  return c;
}

// The use one step along the loop from use k (step +1: the next, -1: the one before), a pole (a
// degenerate edge) passed over: a patch narrowing to a point has its corner across the pole.
size_t step_use(const wefm_cad::CadFace& f, const std::vector<wefm_cad::CadEdgeUse>& loop, size_t k, int step) {
  const size_t n = loop.size(), by = step > 0 ? 1 : n - 1;
  size_t j = (k + by) % n;
  if (f.edges[static_cast<size_t>(loop[j].edge)].vertices.size() < 2) j = (j + by) % n;
  return j;
}

}  // namespace

std::array<double, 3> facet_cross(const wefm_cad::CadFace& f, size_t t) {
  const double *a = at(f, f.triangles[3 * t]), *b = at(f, f.triangles[3 * t + 1]), *c = at(f, f.triangles[3 * t + 2]);
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  return {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
}

std::array<double, 3> facet_normal(const wefm_cad::CadFace& f, size_t t) {
  std::array<double, 3> n = facet_cross(f, t);
  const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  for (double& x : n) x = len > 0 ? x / len : 0;
  return n;
}

// The angle is the turn of the loop seen along the facets' normal at the corner, so a corner of 350
// degrees (a notch) is not taken for one of 10.
std::vector<FaceCorner> face_corners(const wefm_cad::CadFace& f) {
  std::vector<FaceCorner> out;
  std::map<int32_t, std::array<double, 3>> normal;  // at the corner vertices: sum of the facet normals around
  for (const auto& loop : f.loops)
    for (const auto& u : loop) {
      const auto c = chain(f, u);
      if (!c.empty()) normal[c.front()] = {0, 0, 0};
    }
  for (size_t t = 0; 3 * t + 2 < f.triangles.size(); ++t)
    for (size_t c = 0; c < 3; ++c) {
      const auto it = normal.find(f.triangles[3 * t + c]);
      if (it == normal.end()) continue;
      const auto n = facet_normal(f, t);
      for (size_t k = 0; k < 3; ++k) it->second[k] += n[k];
    }
  for (size_t l = 0; l < f.loops.size(); ++l) {
    const auto& loop = f.loops[l];
    for (size_t k = 0; k < loop.size(); ++k) {
      const size_t next = step_use(f, loop, k, +1);
      const auto in = chain(f, loop[k]), out_chain = chain(f, loop[next]);
      if (in.size() < 2 || out_chain.size() < 2 || in.back() != out_chain.front()) continue;
      const double *p = at(f, in[in.size() - 2]), *q = at(f, in.back()), *r = at(f, out_chain[1]);
      const double a[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]}, b[3] = {r[0] - q[0], r[1] - q[1], r[2] - q[2]};
      const auto& n = normal[in.back()];
      const double cross = (a[1] * b[2] - a[2] * b[1]) * n[0] + (a[2] * b[0] - a[0] * b[2]) * n[1] + (a[0] * b[1] - a[1] * b[0]) * n[2];
      const double nn = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      if (!(nn > 0)) continue;
      const double angle = 180 - degrees(std::atan2(cross / nn, a[0] * b[0] + a[1] * b[1] + a[2] * b[2]));
      out.push_back({angle, {f.edges[static_cast<size_t>(loop[k].edge)].id, f.edges[static_cast<size_t>(loop[next].edge)].id}, in.back(), l, k});
    }
  }
  return out;
}

std::array<long long, 2> edges_beyond(const wefm_cad::CadFace& f, const FaceCorner& c) {
  const auto& loop = f.loops[c.loop];
  const size_t before = step_use(f, loop, c.use, -1), next = step_use(f, loop, c.use, +1), after = step_use(f, loop, next, +1);
  auto id = [&](size_t k) { return k == c.use || k == next ? -1LL : f.edges[static_cast<size_t>(loop[k].edge)].id; };
  return {id(before), id(after)};
}

std::vector<FaceCorner> sharp_corners(const wefm_cad::CadFace& f, double below) {
  std::vector<FaceCorner> out = face_corners(f);
  out.erase(std::remove_if(out.begin(), out.end(), [&](const FaceCorner& c) { return !(c.degrees < below); }), out.end());
  std::stable_sort(out.begin(), out.end(), [](const FaceCorner& a, const FaceCorner& b) { return a.degrees < b.degrees; });
  return out;
}

}  // namespace wefm_cli
