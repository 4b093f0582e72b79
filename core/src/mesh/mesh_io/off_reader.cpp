// ASCII OFF ("OFF", "COFF", "NOFF", "STOFF"... : extra per-vertex or per-face fields such as
// colours and normals are skipped). Indices are 0-based; polygons are fan-triangulated. Comments
// start with '#'. Binary OFF and higher-dimensional variants (4OFF, nOFF) are refused by name.
#include "file_buffer.hpp"
#include "readers.hpp"
#include "text_scan.hpp"
#include "wefm/core/sys/error.hpp"

namespace wefm::io {

namespace {

class Scanner {
 public:
  Scanner(const FileBuffer& f, const std::string& path) : p_(f.begin()), end_(f.end()), path_(path) {}

  [[noreturn]] void error(const std::string& what) const { fail(Errc::invalid_mesh, path_ + ":" + std::to_string(line_) + ": " + what); }

  // Moves to the next token across blanks, line ends and comments; false at the end of the file.
  bool next_token() {
    while (p_ < end_) {
      p_ = skip_blanks(p_);
      if (*p_ == '#') p_ = next_line(p_, end_) - 1;
      if (*p_ == '\n') {
        if (p_ >= end_) return false;
        ++line_;
        ++p_;
        continue;
      }
      return true;
    }
    return false;
  }
  std::string word() {
    if (!next_token()) error("unexpected end of file");
    const char* s = p_;
    while (!is_blank(*p_) && *p_ != '\n') ++p_;
    return std::string(s, p_);
  }
  double real(const char* what) {
    double v = 0;
    const char* q = next_token() ? scan_double(p_, end_, v) : nullptr;
    if (!q) error(std::string("expected ") + what);
    p_ = q;
    return v;
  }
  long long integer(const char* what) {
    long long v = 0;
    const char* q = next_token() ? scan_integer(p_, v) : nullptr;
    if (!q || !(is_blank(*q) || *q == '\n' || *q == '#')) error(std::string("expected ") + what);
    p_ = q;
    return v;
  }
  // Drops what is left of the current line (colours, normals).
  void end_record() {
    if (p_ < end_ && *p_ != '\n') p_ = next_line(p_, end_) - 1;
  }
  // True if the rest of the current line holds a token.
  bool more_on_line() {
    p_ = skip_blanks(p_);
    return *p_ != '\n' && *p_ != '#';
  }
  bool at_digit() const { return is_digit(*p_); }

 private:
  const char* p_;
  const char* end_;
  const std::string& path_;
  std::size_t line_ = 1;
};

}  // namespace

ReadResult read_off(const std::string& path) {
  const FileBuffer file(path);
  Scanner s(file, path);
  const std::string magic = s.word();
  if (magic.size() < 3 || magic.compare(magic.size() - 3, 3, "OFF") != 0) s.error("not an OFF file (the first word is '" + magic + "')");
  if (magic.find('4') != std::string::npos || magic.find('n') != std::string::npos) s.error(magic + " (not 3D) is not supported");
  if (s.more_on_line() && !s.at_digit()) {  // "OFF 8 6 0" on one line is accepted too
    const std::string w = s.word();
    if (w == "BINARY") fail(Errc::unsupported, path + ": binary OFF is not supported (use ASCII OFF, OBJ, PLY or STL)");
    s.error("unexpected '" + w + "' after " + magic);
  }
  const long long nv = s.integer("the vertex count");
  const long long nf = s.integer("the face count");
  s.end_record();  // the edge count, if any, is not used
  if (nv < 0 || nf < 0 || nv > 0x7fffffffLL || nf > 0x7fffffffLL) s.error("vertex or face count out of range");
  // Each vertex takes at least 6 bytes ("0 0 0\n") and each face 8: refuse impossible counts before
  // allocating for them.
  if (6.0 * static_cast<double>(nv) + 8.0 * static_cast<double>(nf) > static_cast<double>(file.size()) + 1)
    s.error("the vertex and face counts need more data than the file holds (truncated file?)");
  ReadResult r;
  r.mesh.vertices.resize(static_cast<std::size_t>(nv));
  for (Vec3& v : r.mesh.vertices) {
    for (int k = 0; k < 3; ++k) v[k] = s.real("a vertex coordinate");
    s.end_record();
  }
  r.mesh.triangles.reserve(static_cast<std::size_t>(nf));
  std::vector<Index> poly;
  for (long long f = 0; f < nf; ++f) {
    const long long n = s.integer("a face's vertex count");
    if (n < 3) s.error("face " + std::to_string(f) + " has " + std::to_string(n) + " vertices (at least 3 needed)");
    poly.clear();
    for (long long k = 0; k < n; ++k) {
      const long long v = s.integer("a vertex index");
      if (v < 0 || v >= nv) s.error("face " + std::to_string(f) + ": vertex index " + std::to_string(v) + " is out of range [0, " + std::to_string(nv) + ")");
      poly.push_back(static_cast<Index>(v));
    }
    add_fan(r.mesh.triangles, poly.data(), poly.size());
    s.end_record();
  }
  if (r.mesh.triangles.empty()) fail(Errc::invalid_mesh, path + ": no faces found");
  return r;
}

}  // namespace wefm::io
