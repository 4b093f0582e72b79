// STL, binary or ASCII. Binary is recognised by its size (84 + 50 x the triangle count in the
// header), since ASCII files are not the only ones starting with "solid". Corners are merged into
// shared vertices by merge_corners.
#include <cstdint>
#include <cstring>

#include "file_buffer.hpp"
#include "readers.hpp"
#include "text_scan.hpp"
#include "wefm/core/sys/error.hpp"

namespace wefm::io {

ReadResult read_stl(const std::string& path, double merge_tolerance) {
  const FileBuffer file(path);
  const char* data = file.begin();
  std::vector<Vec3> corners;
  bool binary = false;
  std::uint32_t n = 0;
  if (file.size() >= 84) {
    std::memcpy(&n, data + 80, 4);
    binary = file.size() == 84 + static_cast<std::size_t>(n) * 50;
  }
  if (binary) {
    corners.resize(static_cast<std::size_t>(n) * 3);
    for (std::uint32_t t = 0; t < n; ++t) {
      const char* rec = data + 84 + static_cast<std::size_t>(t) * 50 + 12;  // past the normal
      for (int k = 0; k < 3; ++k) {
        float f[3];
        std::memcpy(f, rec + 12 * k, 12);
        corners[3 * static_cast<std::size_t>(t) + static_cast<std::size_t>(k)] = Vec3(f[0], f[1], f[2]);
      }
    }
  } else {
    if (file.size() < 5 || std::memcmp(data, "solid", 5) != 0)
      fail(Errc::invalid_mesh, path + ": neither ASCII STL (no 'solid') nor binary STL (size does not match the triangle count)");
    const char* p = data;
    const char* const end = file.end();
    corners.reserve(file.size() / 80);  // an ASCII facet takes about 250 bytes for its 3 corners
    while (p < end) {
      const char* v = static_cast<const char*>(memmem(p, static_cast<std::size_t>(end - p), "vertex", 6));
      if (!v) break;
      const char* q = v + 6;
      Vec3 c;
      for (int k = 0; k < 3; ++k) {
        while (q < end && (is_blank(*q) || *q == '\n')) ++q;
        q = scan_double(q, end, c[k]);
        if (!q) fail(Errc::invalid_mesh, path + ": bad vertex coordinate in ASCII STL");
      }
      corners.push_back(c);
      p = q;
    }
    if (corners.size() % 3) fail(Errc::invalid_mesh, path + ": ASCII STL vertex count is not a multiple of 3");
  }
  return merge_corners(corners, merge_tolerance, path);
}

}  // namespace wefm::io
