#pragma once
// Small analytic test faces, built in code so every test states its geometry.
#include <cmath>
#include <functional>

#include "wefm/core/mesh/trimesh.hpp"

namespace wefm::test {

// Regular grid over [0,1]^2 with `n` x `m` cells mapped through `f(u, v)`; triangles CCW in (u, v).
inline TriMesh grid(int n, int m, const std::function<Vec3(double, double)>& f, bool jitter = false) {
  TriMesh t;
  for (int j = 0; j <= m; ++j)
    for (int i = 0; i <= n; ++i) {
      double u = double(i) / n, v = double(j) / m;
      if (jitter && i > 0 && i < n && j > 0 && j < m) {
        u += 0.23 / n * std::sin(12.9898 * i + 78.233 * j);
        v += 0.23 / m * std::cos(39.3468 * i + 11.135 * j);
      }
      t.vertices.push_back(f(u, v));
    }
  auto id = [&](int i, int j) { return static_cast<Index>(j * (n + 1) + i); };
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) {
      const bool flip = (i + j) % 2;
      if (!flip) {
        t.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
        t.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
      } else {
        t.triangles.push_back({id(i, j), id(i + 1, j), id(i, j + 1)});
        t.triangles.push_back({id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
      }
    }
  return t;
}

inline TriMesh flat_patch(int n = 12) {
  return grid(n, n, [](double u, double v) { return Vec3(2.0 * u, 1.3 * v + 0.2 * u, 0.0); }, true);
}

// A cylinder of radius r cut open along a generator: u runs around (less than a full turn closes
// it only when `closed`), v along the axis.
inline TriMesh cut_cylinder(int n = 24, int m = 8, double r = 1.0, double h = 2.0, double sweep = 2 * kPi * 0.999) {
  return grid(n, m, [=](double u, double v) { return Vec3(r * std::cos(sweep * u), r * std::sin(sweep * u), h * v); }, true);
}

// A cone cut open: developable, apex excluded (v starts at 0.3).
inline TriMesh cut_cone(int n = 24, int m = 8) {
  return grid(n, m, [](double u, double v) {
    const double t = 0.3 + 0.7 * v, a = 2 * kPi * 0.95 * u;
    return Vec3(0.6 * t * std::cos(a), 0.6 * t * std::sin(a), t);
  }, true);
}

inline TriMesh hemisphere(int n = 24, int m = 12) {
  return grid(n, m, [](double u, double v) {
    // polar cap minus a tiny hole at the pole would be a disk; use a spherical rectangle instead
    const double th = (u - 0.5) * 2.2, ph = (v - 0.5) * 2.2;
    const Vec3 p(std::tan(th * 0.5), std::tan(ph * 0.5), 1.0);
    return Vec3(p.normalized());
  });
}

inline TriMesh saddle(int n = 20) {
  return grid(n, n, [](double u, double v) {
    const double x = 2 * u - 1, y = 2 * v - 1;
    return Vec3(x, y, 0.5 * (x * x - y * y));
  });
}

}  // namespace wefm::test

namespace wefm::test {

// A helicoid strip: `turns` turns between radii r0 and r1, rising `pitch` per turn (u around, v
// across). Its inner side is much shorter than its outer side, so low-distortion layouts coil.
inline TriMesh helicoid_strip(int n, int m, double turns = 2.0, double r0 = 1.0, double r1 = 1.8, double pitch = 0.9) {
  return grid(n, m, [=](double u, double v) {
    const double a = 2 * kPi * turns * u, r = r0 + (r1 - r0) * v;
    return Vec3(r * std::cos(a), r * std::sin(a), pitch * turns * u);
  });
}

// An open cylinder as an annulus (rows on circles, straight generators): exactly developable.
// `seam` receives the facet edges along the generator at angle 0.
inline TriMesh open_cylinder(int n, int m, std::vector<std::pair<Index, Index>>* seam = nullptr, double r = 1.0, double h = 2.0) {
  TriMesh t;
  for (int j = 0; j <= m; ++j)
    for (int i = 0; i < n; ++i) t.vertices.emplace_back(r * std::cos(2 * kPi * i / n), r * std::sin(2 * kPi * i / n), h * j / m);
  auto id = [&](int i, int j) { return static_cast<Index>(j * n + (i % n)); };
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) {
      t.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      t.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  if (seam)
    for (int j = 0; j < m; ++j) seam->emplace_back(id(0, j), id(0, j + 1));
  return t;
}

// The same cylinder cut open: the generator at angle 0 is doubled, so the face is a disk.
inline TriMesh cut_open_cylinder(int n, int m, double r = 1.0, double h = 2.0) {
  return grid(n, m, [=](double u, double v) { return Vec3(r * std::cos(2 * kPi * u), r * std::sin(2 * kPi * u), h * v); });
}

inline TriMesh transformed(TriMesh t, const Eigen::Matrix3d& R, const Vec3& shift, double scale) {
  for (Vec3& p : t.vertices) p = scale * (R * p) + shift;
  return t;
}

// A disk of radius 1 with three round holes, triangulated on a polar-ish grid by dropping cells.
inline TriMesh disk_with_holes() {
  TriMesh g = grid(40, 40, [](double u, double v) { return Vec3(2 * u - 1, 2 * v - 1, 0.0); });
  const Vec3 holes[3] = {Vec3(-0.4, 0.3, 0), Vec3(0.35, 0.35, 0), Vec3(0.0, -0.4, 0)};
  TriMesh out;
  out.vertices = g.vertices;
  for (const Tri& t : g.triangles) {
    const Vec3 c = (g.vertices[t[0]] + g.vertices[t[1]] + g.vertices[t[2]]) / 3.0;
    bool keep = c.norm() < 0.95;
    for (const Vec3& h : holes) keep = keep && (c - h).norm() > 0.18;
    if (keep) out.triangles.push_back(t);
  }
  // compact vertices
  std::vector<Index> map(out.vertices.size(), -1);
  TriMesh r;
  for (Tri t : out.triangles) {
    for (Index& v : t) {
      if (map[v] < 0) {
        map[v] = static_cast<Index>(r.vertices.size());
        r.vertices.push_back(out.vertices[v]);
      }
      v = map[v];
    }
    r.triangles.push_back(t);
  }
  return r;
}

}  // namespace wefm::test
