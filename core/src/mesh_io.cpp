#include "wefm/core/mesh_io.hpp"

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <unordered_map>

#include "wefm/core/error.hpp"

namespace wefm {

namespace {

std::string lower_ext(const std::string& path) {
  const auto dot = path.find_last_of('.');
  std::string e = dot == std::string::npos ? "" : path.substr(dot + 1);
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return e;
}

std::string slurp(const std::string& path) {
  std::unique_ptr<FILE, int (*)(FILE*)> f(std::fopen(path.c_str(), "rb"), std::fclose);
  if (!f) fail(Errc::io, "cannot open '" + path + "' for reading: " + std::strerror(errno));
  std::string data;
  char buf[1 << 16];
  size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, f.get())) > 0) data.append(buf, n);
  if (std::ferror(f.get())) fail(Errc::io, "error reading '" + path + "'");
  return data;
}

const char* skip_ws(const char* p, const char* e) {
  while (p < e && (*p == ' ' || *p == '\t' || *p == '\r')) ++p;
  return p;
}

ReadResult read_obj(const std::string& path) {
  const std::string data = slurp(path);
  ReadResult r;
  const char* p = data.data();
  const char* end = p + data.size();
  size_t line = 0;
  std::vector<Index> poly;
  while (p < end) {
    ++line;
    const char* eol = static_cast<const char*>(std::memchr(p, '\n', static_cast<size_t>(end - p)));
    if (!eol) eol = end;
    const char* q = skip_ws(p, eol);
    if (q + 1 < eol && q[0] == 'v' && (q[1] == ' ' || q[1] == '\t')) {
      Vec3 v;
      q += 2;
      for (int k = 0; k < 3; ++k) {
        q = skip_ws(q, eol);
        auto res = std::from_chars(q, eol, v[k]);
        if (res.ec != std::errc()) fail(Errc::io, path + ":" + std::to_string(line) + ": bad vertex coordinate");
        q = res.ptr;
      }
      r.mesh.vertices.push_back(v);
    } else if (q + 1 < eol && q[0] == 'f' && (q[1] == ' ' || q[1] == '\t')) {
      q += 2;
      poly.clear();
      while (true) {
        q = skip_ws(q, eol);
        if (q >= eol) break;
        long long idx = 0;
        auto res = std::from_chars(q, eol, idx);
        if (res.ec != std::errc()) fail(Errc::io, path + ":" + std::to_string(line) + ": bad face index");
        q = res.ptr;
        while (q < eol && *q != ' ' && *q != '\t' && *q != '\r') ++q;  // skip /vt/vn
        const long long nv = static_cast<long long>(r.mesh.vertices.size());
        const long long v = idx < 0 ? nv + idx : idx - 1;
        if (idx == 0 || v < 0 || v > 0x7fffffffLL) fail(Errc::io, path + ":" + std::to_string(line) + ": face index " + std::to_string(idx) + " is out of range");
        poly.push_back(static_cast<Index>(v));
      }
      if (poly.size() < 3) fail(Errc::io, path + ":" + std::to_string(line) + ": a face needs at least 3 vertices");
      for (size_t k = 1; k + 1 < poly.size(); ++k) r.mesh.triangles.push_back({poly[0], poly[k], poly[k + 1]});
    }
    p = eol + 1;
  }
  // Indices may refer forward (vertices after faces); check once all vertices are known.
  for (const Tri& t : r.mesh.triangles)
    for (Index v : t)
      if (static_cast<size_t>(v) >= r.mesh.vertices.size()) fail(Errc::io, path + ": face index " + std::to_string(v + 1) + " exceeds the " + std::to_string(r.mesh.vertices.size()) + " vertices");
  if (r.mesh.triangles.empty()) fail(Errc::io, path + ": no faces found");
  return r;
}

// Merge STL corners: exact duplicates always, then those within `tol` through a grid.
ReadResult merge_corners(const std::vector<Vec3>& corners, double tol, const std::string& path) {
  ReadResult r;
  if (corners.empty()) fail(Errc::io, path + ": no triangles found");
  Vec3 lo = corners[0], hi = corners[0];
  for (const Vec3& c : corners) {
    if (!c.allFinite()) fail(Errc::io, path + ": a vertex has a NaN or infinite coordinate");
    lo = lo.cwiseMin(c);
    hi = hi.cwiseMax(c);
  }
  const double diag = (hi - lo).norm();
  const double eps = (tol > 0 ? tol : 1e-9) * (diag > 0 ? diag : 1.0);
  struct Hash {
    size_t operator()(const std::array<long long, 3>& k) const { return std::hash<long long>()(k[0] * 73856093LL ^ k[1] * 19349663LL ^ k[2] * 83492791LL); }
  };
  std::unordered_map<std::array<long long, 3>, std::vector<Index>, Hash> grid;
  std::vector<Index> map(corners.size());
  std::int64_t exact = 0, near = 0;
  for (size_t i = 0; i < corners.size(); ++i) {
    const Vec3& c = corners[i];
    std::array<long long, 3> k{static_cast<long long>(std::floor((c[0] - lo[0]) / eps)), static_cast<long long>(std::floor((c[1] - lo[1]) / eps)),
                               static_cast<long long>(std::floor((c[2] - lo[2]) / eps))};
    Index found = -1;
    for (long long dx = -1; dx <= 1 && found < 0; ++dx)
      for (long long dy = -1; dy <= 1 && found < 0; ++dy)
        for (long long dz = -1; dz <= 1 && found < 0; ++dz) {
          auto it = grid.find({k[0] + dx, k[1] + dy, k[2] + dz});
          if (it == grid.end()) continue;
          for (Index v : it->second)
            if ((r.mesh.vertices[static_cast<size_t>(v)] - c).norm() <= eps) {
              found = v;
              break;
            }
        }
    if (found >= 0) {
      (r.mesh.vertices[static_cast<size_t>(found)] == c ? exact : near)++;
      map[i] = found;
    } else {
      map[i] = static_cast<Index>(r.mesh.vertices.size());
      grid[k].push_back(map[i]);
      r.mesh.vertices.push_back(c);
    }
  }
  for (size_t t = 0; t + 2 < corners.size(); t += 3) r.mesh.triangles.push_back({map[t], map[t + 1], map[t + 2]});
  r.merged_vertices = near;
  (void)exact;
  return r;
}

ReadResult read_stl(const std::string& path, double tol) {
  const std::string data = slurp(path);
  std::vector<Vec3> corners;
  // Binary if the size matches the triangle count in the header (ASCII files may start with "solid" too).
  bool binary = false;
  if (data.size() >= 84) {
    std::uint32_t n;
    std::memcpy(&n, data.data() + 80, 4);
    binary = data.size() == 84 + static_cast<size_t>(n) * 50;
  }
  if (binary) {
    std::uint32_t n;
    std::memcpy(&n, data.data() + 80, 4);
    corners.reserve(static_cast<size_t>(n) * 3);
    for (std::uint32_t t = 0; t < n; ++t) {
      const char* rec = data.data() + 84 + static_cast<size_t>(t) * 50 + 12;
      for (int k = 0; k < 3; ++k) {
        float f[3];
        std::memcpy(f, rec + 12 * k, 12);
        corners.emplace_back(f[0], f[1], f[2]);
      }
    }
  } else {
    if (data.compare(0, 5, "solid") != 0) fail(Errc::io, path + ": neither ASCII STL (no 'solid') nor binary STL (size does not match the triangle count)");
    const char* p = data.data();
    const char* end = p + data.size();
    while (p < end) {
      const char* v = static_cast<const char*>(memmem(p, static_cast<size_t>(end - p), "vertex", 6));
      if (!v) break;
      const char* q = v + 6;
      Vec3 c;
      for (int k = 0; k < 3; ++k) {
        while (q < end && std::isspace(static_cast<unsigned char>(*q))) ++q;
        auto res = std::from_chars(q, end, c[k]);
        if (res.ec != std::errc()) fail(Errc::io, path + ": bad vertex coordinate in ASCII STL");
        q = res.ptr;
      }
      corners.push_back(c);
      p = q;
    }
    if (corners.size() % 3) fail(Errc::io, path + ": ASCII STL vertex count is not a multiple of 3");
  }
  return merge_corners(corners, tol, path);
}

ReadResult read_openmesh(const std::string& path) {
  using Mesh = OpenMesh::PolyMesh_ArrayKernelT<>;
  Mesh m;
  OpenMesh::IO::Options ropt;
  if (!OpenMesh::IO::read_mesh(m, path, ropt)) fail(Errc::io, "cannot read '" + path + "' (missing, unreadable, or not a valid mesh file)");
  ReadResult r;
  r.mesh.vertices.reserve(m.n_vertices());
  for (auto vh : m.vertices()) {
    const auto p = m.point(vh);
    r.mesh.vertices.emplace_back(p[0], p[1], p[2]);
  }
  for (auto fh : m.faces()) {
    std::vector<Index> poly;
    for (auto vh : m.fv_range(fh)) poly.push_back(static_cast<Index>(vh.idx()));
    for (size_t k = 1; k + 1 < poly.size(); ++k) r.mesh.triangles.push_back({poly[0], poly[k], poly[k + 1]});
  }
  if (r.mesh.triangles.empty()) fail(Errc::io, path + ": no faces found");
  return r;
}

}  // namespace

ReadResult read_mesh(const std::string& path, double merge_tolerance) {
  const std::string ext = lower_ext(path);
  if (ext == "obj") return read_obj(path);
  if (ext == "stl") return read_stl(path, merge_tolerance);
  if (ext == "off" || ext == "ply") return read_openmesh(path);
  fail(Errc::unsupported, "unsupported mesh format '." + ext + "' for '" + path + "' (OBJ, OFF, STL, PLY)");
}

void write_obj_uv(const std::string& path, const TriMesh& m, const Topology& tp, const VectorXc& uv) {
  std::unique_ptr<FILE, int (*)(FILE*)> f(std::fopen(path.c_str(), "wb"), std::fclose);
  if (!f) fail(Errc::io, "cannot open '" + path + "' for writing: " + std::strerror(errno));
  std::string buf;
  buf.reserve(1 << 20);
  char tmp[64];
  auto flush = [&] {
    if (std::fwrite(buf.data(), 1, buf.size(), f.get()) != buf.size()) fail(Errc::io, "error writing '" + path + "'");
    buf.clear();
  };
  auto num = [&](double x) {
    auto res = std::to_chars(tmp, tmp + sizeof tmp, x);
    buf.append(tmp, res.ptr);
  };
  auto integer = [&](long long x) {
    auto res = std::to_chars(tmp, tmp + sizeof tmp, x);
    buf.append(tmp, res.ptr);
  };
  buf += "# wefm flattened face: v = 3D, vt = UV per vertex use\n";
  for (const Vec3& p : m.vertices) {
    buf += "v ";
    num(p[0]);
    buf += ' ';
    num(p[1]);
    buf += ' ';
    num(p[2]);
    buf += '\n';
    if (buf.size() > (1 << 20)) flush();
  }
  for (Index u = 0; u < static_cast<Index>(uv.size()); ++u) {
    buf += "vt ";
    num(uv[u].real());
    buf += ' ';
    num(uv[u].imag());
    buf += '\n';
    if (buf.size() > (1 << 20)) flush();
  }
  for (size_t t = 0; t < m.triangles.size(); ++t) {
    buf += 'f';
    for (int j = 0; j < 3; ++j) {
      buf += ' ';
      integer(m.triangles[t][j] + 1LL);
      buf += '/';
      integer(tp.corner_use[3 * t + static_cast<size_t>(j)] + 1LL);
    }
    buf += '\n';
    if (buf.size() > (1 << 20)) flush();
  }
  flush();
  if (std::fflush(f.get()) != 0) fail(Errc::io, "error writing '" + path + "'");
}

}  // namespace wefm
