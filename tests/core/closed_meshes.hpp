#pragma once
// Closed and ring-shaped test faces for the automatic cut, built in code.
#include <array>
#include <cmath>
#include <map>

#include "wefm/core/mesh/trimesh.hpp"

namespace wefm::test {

// Icosahedron subdivided `levels` times, projected on the unit sphere, then scaled per axis.
inline TriMesh icosphere(int levels, const Vec3& scale = Vec3(1, 1, 1)) {
  const double p = (1 + std::sqrt(5.0)) / 2;
  TriMesh t;
  t.vertices = {Vec3(-1, p, 0), Vec3(1, p, 0), Vec3(-1, -p, 0), Vec3(1, -p, 0), Vec3(0, -1, p), Vec3(0, 1, p),
                Vec3(0, -1, -p), Vec3(0, 1, -p), Vec3(p, 0, -1), Vec3(p, 0, 1), Vec3(-p, 0, -1), Vec3(-p, 0, 1)};
  t.triangles = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                 {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8}, {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<Index, Index>, Index> mid;
    auto midpoint = [&](Index a, Index b) {
      auto key = std::make_pair(std::min(a, b), std::max(a, b));
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      t.vertices.push_back(0.5 * (t.vertices[static_cast<size_t>(a)] + t.vertices[static_cast<size_t>(b)]));
      return mid[key] = static_cast<Index>(t.vertices.size() - 1);
    };
    std::vector<Tri> next;
    for (const Tri& f : t.triangles) {
      const Index a = midpoint(f[0], f[1]), b = midpoint(f[1], f[2]), c = midpoint(f[2], f[0]);
      next.push_back({f[0], a, c});
      next.push_back({f[1], b, a});
      next.push_back({f[2], c, b});
      next.push_back({a, b, c});
    }
    t.triangles = std::move(next);
  }
  for (Vec3& v : t.vertices) v = v.normalized().cwiseProduct(scale);
  return t;
}

// Closed box of size `dims`, each side a grid of cells of about the same size (k along the longest side).
inline TriMesh closed_box(const Vec3& dims, int k) {
  std::array<int, 3> n;
  const double longest = dims.maxCoeff();
  for (int a = 0; a < 3; ++a) n[a] = std::max(1, static_cast<int>(std::lround(k * dims[a] / longest)));
  TriMesh t;
  std::map<std::array<int, 3>, Index> id;
  auto vertex = [&](std::array<int, 3> q) {
    auto it = id.find(q);
    if (it != id.end()) return it->second;
    t.vertices.emplace_back(dims[0] * q[0] / n[0], dims[1] * q[1] / n[1], dims[2] * q[2] / n[2]);
    return id[q] = static_cast<Index>(t.vertices.size() - 1);
  };
  for (int a = 0; a < 3; ++a) {
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    for (int side : {0, n[a]})
      for (int i = 0; i < n[b]; ++i)
        for (int j = 0; j < n[c]; ++j) {
          auto at = [&](int di, int dj) {
            std::array<int, 3> q{};
            q[a] = side;
            q[b] = i + di;
            q[c] = j + dj;
            return vertex(q);
          };
          const Index p00 = at(0, 0), p10 = at(1, 0), p11 = at(1, 1), p01 = at(0, 1);
          if (side)  // outward normal +a: counter-clockwise in (b, c)
            t.triangles.insert(t.triangles.end(), {Tri{p00, p10, p11}, Tri{p00, p11, p01}});
          else
            t.triangles.insert(t.triangles.end(), {Tri{p00, p11, p10}, Tri{p00, p01, p11}});
        }
  }
  return t;
}

// Torus (genus 1): n around the axis, m around the tube.
inline TriMesh torus(int n, int m, double R = 2.0, double r = 0.6) {
  TriMesh t;
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) {
      const double u = 2 * kPi * i / n, v = 2 * kPi * j / m;
      t.vertices.emplace_back((R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v));
    }
  auto id = [&](int i, int j) { return static_cast<Index>((j % m) * n + (i % n)); };
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) {
      t.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      t.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return t;
}

// Flat ring between radii r0 and r1 (an annulus that is exact without any cut).
inline TriMesh flat_ring(int n, int m, double r0 = 1.0, double r1 = 2.0) {
  TriMesh t;
  for (int j = 0; j <= m; ++j)
    for (int i = 0; i < n; ++i) {
      const double r = r0 + (r1 - r0) * j / m, a = 2 * kPi * i / n;
      t.vertices.emplace_back(r * std::cos(a), r * std::sin(a), 0.0);
    }
  auto id = [&](int i, int j) { return static_cast<Index>(j * n + (i % n)); };
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) {
      t.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      t.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return t;
}

}  // namespace wefm::test
