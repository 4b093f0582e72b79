// OBJ: `v x y z [w]` and `f a b c ...` with `a`, `a/t`, `a/t/n` or `a//n` corners, 1-based or
// negative (relative to the vertices read so far), polygons fan-triangulated, forward references
// allowed; every other statement (vt, vn, g, o, s, usemtl, l, #...) is skipped.
#include "readers.hpp"
#include "file_buffer.hpp"
#include "text_scan.hpp"
#include "wefm/core/sys/error.hpp"
#include "wefm/core/sys/huge_pages.hpp"

namespace wefm::io {

namespace {

[[noreturn]] void fail_at(const std::string& path, std::size_t line, const std::string& what) {
  fail(Errc::invalid_mesh, path + ":" + std::to_string(line) + ": " + what);
}

}  // namespace

ReadResult read_obj(const std::string& path) {
  const FileBuffer file(path);
  const char* p = file.begin();
  const char* const end = file.end();
  ReadResult r;
  auto& vertices = r.mesh.vertices;
  auto& triangles = r.mesh.triangles;
  // A typical line is 25-40 bytes and a closed-ish mesh has twice as many triangles as vertices:
  // reserving from the size avoids most regrowth without a counting pass.
  reserve_huge(vertices, file.size() / 100);
  reserve_huge(triangles, file.size() / 50);
  std::vector<Index> poly;
  std::size_t line = 0;
  while (p < end) {
    ++line;
    const char* q = skip_blanks(p);
    if (q[0] == 'v' && (q[1] == ' ' || q[1] == '\t')) {
      Vec3 v;
      q += 2;
      for (int k = 0; k < 3; ++k) {
        q = scan_double(skip_blanks(q), end, v[k]);
        if (!q) fail_at(path, line, "bad vertex coordinate");
      }
      vertices.push_back(v);
    } else if (q[0] == 'f' && (q[1] == ' ' || q[1] == '\t')) {
      q += 2;
      poly.clear();
      while (true) {
        q = skip_blanks(q);
        if (*q == '\n') break;
        long long idx = 0;
        const char* after = scan_integer(q, idx);
        if (!after) fail_at(path, line, "bad face index");
        q = after;
        while (!is_blank(*q) && *q != '\n') ++q;  // the /vt/vn part
        const long long nv = static_cast<long long>(vertices.size());
        const long long v = idx < 0 ? nv + idx : idx - 1;
        if (idx == 0 || v < 0 || v > 0x7fffffffLL) fail_at(path, line, "face index " + std::to_string(idx) + " is out of range");
        poly.push_back(static_cast<Index>(v));
      }
      if (poly.size() < 3) fail_at(path, line, "a face needs at least 3 vertices");
      add_fan(triangles, poly.data(), poly.size());
    }
    p = next_line(q, end);
  }
  // Indices may refer forward (vertices after faces); check once all vertices are known.
  const Index nv = static_cast<Index>(std::min<std::size_t>(vertices.size(), 0x7fffffff));
  for (const Tri& t : triangles)
    for (Index v : t)
      if (v >= nv) fail(Errc::invalid_mesh, path + ": face index " + std::to_string(v + 1LL) + " exceeds the " + std::to_string(vertices.size()) + " vertices");
  if (triangles.empty()) fail(Errc::invalid_mesh, path + ": no faces found");
  vertices.shrink_to_fit();
  triangles.shrink_to_fit();
  return r;
}

}  // namespace wefm::io
