#pragma once
// Test faces as plain arrays for the C API, and small RAII helpers. Only <wefm/wefm.h> is used: these
// tests check the library at the boundary a mesher links against.
#include <wefm/wefm.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace wefm_test {

constexpr double kPi = 3.14159265358979323846;

struct Arrays {
  std::vector<double> xyz;    // 3 per vertex
  std::vector<int32_t> tri;   // 3 per triangle
  int64_t nv() const { return static_cast<int64_t>(xyz.size() / 3); }
  int64_t nt() const { return static_cast<int64_t>(tri.size() / 3); }
  void add_vertex(double x, double y, double z) { xyz.insert(xyz.end(), {x, y, z}); }
  void add_tri(int32_t a, int32_t b, int32_t c) { tri.insert(tri.end(), {a, b, c}); }
};

// n x m cells over [0,1]^2 mapped through f; triangles counter-clockwise in (u, v).
inline Arrays grid(int n, int m, const std::function<void(double, double, double*)>& f) {
  Arrays a;
  for (int j = 0; j <= m; ++j)
    for (int i = 0; i <= n; ++i) {
      double p[3];
      f(double(i) / n, double(j) / m, p);
      a.add_vertex(p[0], p[1], p[2]);
    }
  auto id = [&](int i, int j) { return static_cast<int32_t>(j * (n + 1) + i); };
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) {
      a.add_tri(id(i, j), id(i + 1, j), id(i + 1, j + 1));
      a.add_tri(id(i, j), id(i + 1, j + 1), id(i, j + 1));
    }
  return a;
}

inline Arrays flat(int n = 6) {
  return grid(n, n, [](double u, double v, double* p) { p[0] = 2 * u; p[1] = 1.3 * v + 0.2 * u; p[2] = 0; });
}

// A curved, non-developable patch (part of a sphere): the continuation in s has work to do.
inline Arrays cap(int n) {
  return grid(n, n, [](double u, double v, double* p) {
    const double x = std::tan((u - 0.5) * 1.1), y = std::tan((v - 0.5) * 1.1), r = std::sqrt(x * x + y * y + 1);
    p[0] = x / r; p[1] = y / r; p[2] = 1 / r;
  });
}

// Open cylinder (annulus): n around, m rows; the generator at angle 0 joins vertices j*n.
inline Arrays open_cylinder(int n, int m) {
  Arrays a;
  for (int j = 0; j <= m; ++j)
    for (int i = 0; i < n; ++i) a.add_vertex(std::cos(2 * kPi * i / n), std::sin(2 * kPi * i / n), 2.0 * j / m);
  auto id = [&](int i, int j) { return static_cast<int32_t>(j * n + (i % n)); };
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i) {
      a.add_tri(id(i, j), id(i + 1, j), id(i + 1, j + 1));
      a.add_tri(id(i, j), id(i + 1, j + 1), id(i, j + 1));
    }
  return a;
}

inline Arrays octahedron() {
  Arrays a;
  a.xyz = {1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1};
  a.tri = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
  return a;
}

// Owning face handle.
struct Face {
  wefm_face* f = nullptr;
  Face() { wefm_face_create(&f); }
  explicit Face(const Arrays& a) : Face() { last = wefm_face_set_mesh(f, a.nv(), a.xyz.data(), a.nt(), a.tri.data()); }
  ~Face() { wefm_face_release(f); }
  Face(const Face&) = delete;
  Face& operator=(const Face&) = delete;
  operator wefm_face*() const { return f; }
  std::string error() const { return wefm_face_last_error(f); }
  wefm_status last = WEFM_OK;
};

inline std::vector<double> get_uv(wefm_face* f, wefm_status* st = nullptr) {
  int64_t n = 0;
  wefm_status s = wefm_face_get_uv(f, nullptr, 0, &n);
  std::vector<double> uv(static_cast<size_t>(s == WEFM_OK ? n : 0));
  if (s == WEFM_OK) s = wefm_face_get_uv(f, uv.data(), n, &n);
  if (st) *st = s;
  return uv;
}

inline int64_t use_count(wefm_face* f) {
  int64_t n = -1;
  wefm_face_use_count(f, &n);
  return n;
}

inline bool all_finite(const std::vector<double>& v) {
  for (double x : v)
    if (!std::isfinite(x)) return false;
  return true;
}

inline wefm_report report_of(wefm_face* f) {
  wefm_report r;
  wefm_report_init(&r);
  wefm_face_get_report(f, &r);
  return r;
}

inline wefm_options options() {
  wefm_options o;
  wefm_options_init(&o);
  return o;
}

}  // namespace wefm_test
