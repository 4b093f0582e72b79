#include "face_generator.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>

namespace wefm_bench {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Rings of 6k vertices around a centre vertex: nearly equilateral triangles everywhere and
// exactly 6 K^2 triangles, so the size is easy to hit and no sliver spoils the conditioning.
Face bumpy_disk(int64_t target) {
  const int64_t rings = std::max<int64_t>(2, std::llround(std::sqrt(static_cast<double>(target) / 6.0)));
  Face f;
  f.xyz.reserve(static_cast<size_t>(3 * (1 + 3 * rings * (rings + 1))));
  f.tri.reserve(static_cast<size_t>(3 * 6 * rings * rings));
  auto add_vertex = [&](double r, double angle) {
    const double x = r * std::cos(angle), y = r * std::sin(angle);
    // Bumps of a few wavelengths on a shallow bowl: curvature of both signs, still a graph over
    // the disk, so the face is a topological disk with no fold.
    const double z = 0.06 * std::sin(3 * kPi * x) * std::sin(2 * kPi * y) + 0.2 * (x * x - 0.5 * y * y);
    f.xyz.insert(f.xyz.end(), {x, y, z});
  };
  add_vertex(0, 0);
  for (int64_t k = 1; k <= rings; ++k)
    for (int64_t i = 0; i < 6 * k; ++i) add_vertex(static_cast<double>(k) / static_cast<double>(rings), 2 * kPi * static_cast<double>(i) / static_cast<double>(6 * k));
  auto ring_start = [](int64_t k) { return k == 0 ? int64_t{0} : 1 + 3 * k * (k - 1); };
  for (int64_t k = 1; k <= rings; ++k) {
    const int64_t na = k == 1 ? 1 : 6 * (k - 1), nb = 6 * k;
    const int64_t a0 = ring_start(k - 1), b0 = ring_start(k);
    auto inner = [&](int64_t i) { return static_cast<int32_t>(a0 + i % na); };
    auto outer = [&](int64_t j) { return static_cast<int32_t>(b0 + j % nb); };
    if (k == 1) {
      for (int64_t j = 0; j < nb; ++j) f.tri.insert(f.tri.end(), {inner(0), outer(j), outer(j + 1)});
      continue;
    }
    // Merge the two rings by angle; integer comparison of (j+1)/nb with (i+1)/na keeps it exact.
    int64_t i = 0, j = 0;
    while (i < na || j < nb) {
      const bool advance_outer = i == na || (j < nb && (j + 1) * na <= (i + 1) * nb);
      if (advance_outer) {
        f.tri.insert(f.tri.end(), {inner(i), outer(j), outer(j + 1)});
        ++j;
      } else {
        f.tri.insert(f.tri.end(), {inner(i), outer(j), inner(i + 1)});
        ++i;
      }
    }
  }
  return f;
}

struct Hole {
  double x, y, r;
};
// Far enough apart (and from the rim) that no hole touches another at any size.
constexpr Hole kHoles[] = {{-0.55, 0.0, 0.2}, {0.05, 0.12, 0.16}, {0.6, -0.1, 0.22}};

// A 2:1 grid with whole cells removed where their centre falls in a hole. Removing whole cells
// inside a disk never leaves two removed cells touching only at a corner, so every vertex keeps a
// single fan and the face stays a manifold with four boundary loops.
Face holed_plate(int64_t target) {
  double hole_area = 0;
  for (const Hole& h : kHoles) hole_area += kPi * h.r * h.r;
  const double kept = 1.0 - hole_area / 2.0;  // the plate is 2 x 1
  const int64_t ny = std::max<int64_t>(8, std::llround(std::sqrt(static_cast<double>(target) / (4.0 * kept))));
  const int64_t nx = 2 * ny;
  const double h = 1.0 / static_cast<double>(ny);
  auto removed = [&](int64_t i, int64_t j) {
    const double cx = -1.0 + (static_cast<double>(i) + 0.5) * h, cy = -0.5 + (static_cast<double>(j) + 0.5) * h;
    for (const Hole& o : kHoles)
      if ((cx - o.x) * (cx - o.x) + (cy - o.y) * (cy - o.y) < o.r * o.r) return true;
    return false;
  };
  auto grid_id = [&](int64_t i, int64_t j) { return j * (nx + 1) + i; };
  std::vector<int32_t> id(static_cast<size_t>((nx + 1) * (ny + 1)), -1);
  Face f;
  f.tri.reserve(static_cast<size_t>(6 * nx * ny));
  for (int64_t j = 0; j < ny; ++j)
    for (int64_t i = 0; i < nx; ++i) {
      if (removed(i, j)) continue;
      const int64_t a = grid_id(i, j), b = grid_id(i + 1, j), c = grid_id(i + 1, j + 1), d = grid_id(i, j + 1);
      // Alternating diagonals: no preferred direction for the flattening to pick up.
      if ((i + j) % 2 == 0) {
        f.tri.insert(f.tri.end(), {static_cast<int32_t>(a), static_cast<int32_t>(b), static_cast<int32_t>(c)});
        f.tri.insert(f.tri.end(), {static_cast<int32_t>(a), static_cast<int32_t>(c), static_cast<int32_t>(d)});
      } else {
        f.tri.insert(f.tri.end(), {static_cast<int32_t>(a), static_cast<int32_t>(b), static_cast<int32_t>(d)});
        f.tri.insert(f.tri.end(), {static_cast<int32_t>(b), static_cast<int32_t>(c), static_cast<int32_t>(d)});
      }
    }
  // Number the used grid points in grid order so the file has no unreferenced vertex.
  for (int32_t v : f.tri) id[static_cast<size_t>(v)] = 0;
  int32_t next = 0;
  constexpr double R = 0.9;  // bend radius along x: about 64 degrees each way
  for (int64_t j = 0; j <= ny; ++j)
    for (int64_t i = 0; i <= nx; ++i) {
      int32_t& slot = id[static_cast<size_t>(grid_id(i, j))];
      if (slot < 0) continue;
      slot = next++;
      const double x = -1.0 + static_cast<double>(i) * h, y = -0.5 + static_cast<double>(j) * h;
      // Cylinder bend in x plus a parabola in y: doubly curved, so no layout is isometric.
      f.xyz.insert(f.xyz.end(), {R * std::sin(x / R), y, R * (1 - std::cos(x / R)) + 0.3 * y * y});
    }
  for (int32_t& v : f.tri) v = id[static_cast<size_t>(v)];
  return f;
}

// A tube 3 long around the z axis, nt vertices around and nz + 1 rows (nt = 2 nz), its radius
// bulging along z and rippled around it, so no layout is isometric: a cylindrical CAD face meshed
// finely, with the seam a CAD kernel puts along one generator (angle 0). Cut, the column at angle
// 0 is repeated at 2 pi and the face is a topological disk.
Face seamed_tube(int64_t target, bool cut) {
  const int64_t nz = std::max<int64_t>(4, std::llround(std::sqrt(static_cast<double>(target) / 4.0)));
  const int64_t nt = 2 * nz, cols = cut ? nt + 1 : nt;
  Face f;
  f.xyz.reserve(static_cast<size_t>(3 * cols * (nz + 1)));
  for (int64_t j = 0; j <= nz; ++j)
    for (int64_t i = 0; i < cols; ++i) {
      const double t = 2 * kPi * static_cast<double>(i % nt) / static_cast<double>(nt);
      const double z = 3.0 * static_cast<double>(j) / static_cast<double>(nz);
      const double r = 1.0 + 0.25 * std::sin(1.3 * z) + 0.05 * std::cos(3 * t) * std::sin(2 * z);
      f.xyz.insert(f.xyz.end(), {r * std::cos(t), r * std::sin(t), z});
    }
  auto id = [&](int64_t i, int64_t j) { return static_cast<int32_t>(j * cols + (cut ? i : i % nt)); };
  f.tri.reserve(static_cast<size_t>(6 * nt * nz));
  for (int64_t j = 0; j < nz; ++j)
    for (int64_t i = 0; i < nt; ++i) {
      const int32_t a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      f.tri.insert(f.tri.end(), {a, b, c});
      f.tri.insert(f.tri.end(), {a, c, d});
    }
  if (!cut)
    for (int64_t j = 0; j < nz; ++j) f.seam.insert(f.seam.end(), {id(0, j), id(0, j + 1)});
  return f;
}

}  // namespace

Face generate(Shape shape, int64_t target_triangles, bool cut) {
  switch (shape) {
    case Shape::BumpyDisk: return bumpy_disk(target_triangles);
    case Shape::HoledPlate: return holed_plate(target_triangles);
    case Shape::SeamedTube: return seamed_tube(target_triangles, cut);
  }
  return {};
}

const char* shape_name(Shape shape) {
  switch (shape) {
    case Shape::BumpyDisk: return "disk";
    case Shape::HoledPlate: return "plate";
    case Shape::SeamedTube: return "tube";
  }
  return "?";
}

bool parse_shape(const std::string& name, Shape& shape) {
  if (name == "disk") shape = Shape::BumpyDisk;
  else if (name == "plate") shape = Shape::HoledPlate;
  else if (name == "tube") shape = Shape::SeamedTube;
  else return false;
  return true;
}

bool parse_size(const std::string& text, int64_t& size) {
  if (text.empty()) return false;
  double value = 0;
  const char* end = text.data() + text.size();
  auto r = std::from_chars(text.data(), end, value);
  if (r.ec != std::errc() || !(value > 0)) return false;
  double unit = 1;
  if (r.ptr != end) {
    if (r.ptr + 1 != end) return false;
    const char u = *r.ptr;
    if (u == 'k' || u == 'K') unit = 1e3;
    else if (u == 'm' || u == 'M') unit = 1e6;
    else return false;
  }
  size = std::llround(value * unit);
  return size >= 100 && size <= 400000000;
}

std::string size_label(int64_t size) {
  if (size % 1000000 == 0) return std::to_string(size / 1000000) + "M";
  if (size % 1000 == 0) return std::to_string(size / 1000) + "k";
  return std::to_string(size);
}

bool write_obj(const std::string& path, const Face& face) {
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "wb"), std::fclose);
  if (!file) return false;
  std::vector<char> buf(1 << 20);
  size_t n = 0;
  bool ok = true;
  auto flush = [&] {
    if (n && std::fwrite(buf.data(), 1, n, file.get()) != n) ok = false;
    n = 0;
  };
  auto room = [&](size_t k) {
    if (n + k > buf.size()) flush();
  };
  auto put = [&](const char* s) {
    for (; *s; ++s) {
      room(1);
      buf[n++] = *s;
    }
  };
  auto number = [&](auto x) {
    room(32);
    n = static_cast<size_t>(std::to_chars(buf.data() + n, buf.data() + buf.size(), x).ptr - buf.data());
  };
  put("# wefm benchmark face (bench/face_generator.cpp)\n");
  for (int64_t v = 0; v < face.vertices(); ++v) {
    put("v");
    for (int k = 0; k < 3; ++k) {
      put(" ");
      number(face.xyz[static_cast<size_t>(3 * v + k)]);
    }
    put("\n");
  }
  for (int64_t t = 0; t < face.triangles(); ++t) {
    put("f");
    for (int k = 0; k < 3; ++k) {
      put(" ");
      number(int64_t{face.tri[static_cast<size_t>(3 * t + k)]} + 1);
    }
    put("\n");
  }
  flush();
  if (std::fflush(file.get()) != 0) ok = false;
  return ok;
}

bool write_seam(const std::string& path, const Face& face) {
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "wb"), std::fclose);
  if (!file) return false;
  bool ok = std::fputs("# facet edges to cut along (0-based vertex indices), bench/face_generator.cpp\n", file.get()) >= 0;
  for (size_t k = 0; ok && k + 1 < face.seam.size(); k += 2) ok = std::fprintf(file.get(), "%d %d\n", face.seam[k], face.seam[k + 1]) > 0;
  return ok && std::fflush(file.get()) == 0;
}

bool write_stl(const std::string& path, const Face& face) {
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "wb"), std::fclose);
  if (!file) return false;
  std::vector<char> out(84 + 50 * static_cast<size_t>(face.triangles()), 0);
  const auto n = static_cast<std::uint32_t>(face.triangles());
  std::memcpy(out.data() + 80, &n, 4);
  for (int64_t t = 0; t < face.triangles(); ++t) {
    char* rec = out.data() + 84 + 50 * t + 12;  // normal left zero: readers recompute it
    for (int k = 0; k < 3; ++k)
      for (int a = 0; a < 3; ++a) {
        const float x = static_cast<float>(face.xyz[3 * static_cast<size_t>(face.tri[static_cast<size_t>(3 * t + k)]) + static_cast<size_t>(a)]);
        std::memcpy(rec + 12 * k + 4 * a, &x, 4);
      }
  }
  return std::fwrite(out.data(), 1, out.size(), file.get()) == out.size() && std::fflush(file.get()) == 0;
}

}  // namespace wefm_bench
