#include "wefm/core/mesh/mesh_io.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstring>

#include "mesh_io/readers.hpp"
#include "wefm/core/sys/atomic_file.hpp"
#include "wefm/core/sys/error.hpp"

namespace wefm {

namespace {

std::string lower_ext(const std::string& path) {
  const auto dot = path.find_last_of('.');
  std::string e = dot == std::string::npos ? "" : path.substr(dot + 1);
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return e;
}

// One large buffer filled with std::to_chars and written in 4 MB blocks: per-number stdio or
// iostream formatting would dominate the time of a million-triangle file. The file is replaced
// whole on close() or not at all (AtomicFile).
class ObjWriter {
 public:
  explicit ObjWriter(const std::string& path) : file_(path), buf_(kBlock + 256) {}
  void text(const char* s) {
    const std::size_t k = std::strlen(s);
    if (n_ + k > buf_.size()) flush();
    std::memcpy(buf_.data() + n_, s, k);
    n_ += k;
  }
  void chr(char c) { buf_[n_++] = c; }
  template <class T>
  void number(T x) {  // shortest text that reads back to the same value
    n_ = static_cast<std::size_t>(std::to_chars(buf_.data() + n_, buf_.data() + buf_.size(), x).ptr - buf_.data());
  }
  // Call once per line: every line is far shorter than the 256 bytes of slack kept here.
  void end_line() {
    buf_[n_++] = '\n';
    if (n_ >= kBlock) flush();
  }
  void close() {
    flush();
    file_.commit();
  }

 private:
  static constexpr std::size_t kBlock = std::size_t{4} << 20;
  void flush() {
    file_.write(buf_.data(), n_);
    n_ = 0;
  }
  AtomicFile file_;
  std::vector<char> buf_;
  std::size_t n_ = 0;
};

}  // namespace

ReadResult read_mesh(const std::string& path, double merge_tolerance) {
  const std::string ext = lower_ext(path);
  if (ext == "obj") return io::read_obj(path);
  if (ext == "stl") return io::read_stl(path, merge_tolerance);
  if (ext == "off") return io::read_off(path);
  if (ext == "ply") return io::read_ply(path);
  fail(Errc::unsupported, "unsupported mesh format '." + ext + "' for '" + path + "' (OBJ, OFF, STL, PLY)");
}

void write_obj_uv(const std::string& path, const TriMesh& m, const Topology& tp, const VectorXc& uv) {
  ObjWriter w(path);
  w.text("# wefm flattened face: v = 3D, vt = UV per vertex use\n");
  for (const Vec3& p : m.vertices) {
    w.text("v ");
    w.number(p[0]);
    w.chr(' ');
    w.number(p[1]);
    w.chr(' ');
    w.number(p[2]);
    w.end_line();
  }
  for (Index u = 0; u < static_cast<Index>(uv.size()); ++u) {
    w.text("vt ");
    w.number(uv[u].real());
    w.chr(' ');
    w.number(uv[u].imag());
    w.end_line();
  }
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    w.chr('f');
    for (std::size_t j = 0; j < 3; ++j) {
      w.chr(' ');
      w.number(m.triangles[t][j] + 1LL);
      w.chr('/');
      w.number(tp.corner_use[3 * t + j] + 1LL);
    }
    w.end_line();
  }
  w.close();
}

}  // namespace wefm
