#pragma once
// The lines of a Wavefront OBJ file, written once for the library (a flattened face's UV layout, a
// domain mesh: core/mesh/obj_writer) and the tool (its OBJ outputs: apps/wefm/mesh_formats), so
// both spell the format alike. `Out` is a TextBuffer (text_buffer.hpp) or a type with its put(),
// integer() and real(). Indices are given 0-based and written 1-based, as OBJ counts.
#include <cstddef>
#include <cstdint>
#include <string_view>

namespace wefm_common {

template <class Out>
class ObjLines {
 public:
  // `digits` 0: each real as the shortest text that reads back to the same double; otherwise as
  // printf's %.{digits}g (the tool keeps %.17g where a command wrote it so before).
  explicit ObjLines(Out& out, int digits = 0) : out_(out), digits_(digits) {}

  void comment(std::string_view text) {  // "# text"
    out_.put("# ");
    one_line(text);
  }
  void group(std::string_view name) {  // "g name"
    out_.put("g ");
    one_line(name);
  }
  void vertex(double x, double y, double z) {  // "v x y z"
    out_.put("v ");
    out_.real(x, digits_);
    out_.put(' ');
    out_.real(y, digits_);
    out_.put(' ');
    out_.real(z, digits_);
    out_.put('\n');
  }
  void texture(double u, double v) {  // "vt u v"
    out_.put("vt ");
    out_.real(u, digits_);
    out_.put(' ');
    out_.real(v, digits_);
    out_.put('\n');
  }
  // "f v1/t1 v2/t2 ...": corner k is vertex v[k] with texture vertex t[k]; "f v1 v2 ..." when t is
  // null (a mesh without UVs).
  template <class I>
  void face(const I* v, const I* t, std::size_t corners) {
    out_.put('f');
    for (std::size_t k = 0; k < corners; ++k) {
      out_.put(' ');
      out_.integer(static_cast<std::int64_t>(v[k]) + 1);
      if (!t) continue;
      out_.put('/');
      out_.integer(static_cast<std::int64_t>(t[k]) + 1);
    }
    out_.put('\n');
  }

 private:
  // A line break inside a comment or a name would start a line of another kind.
  void one_line(std::string_view text) {
    for (std::size_t start = 0;;) {
      const std::size_t end = text.find_first_of("\r\n", start);
      out_.put(text.substr(start, end - start));
      if (end == std::string_view::npos) break;
      out_.put(' ');
      start = end + 1;
    }
    out_.put('\n');
  }

  Out& out_;
  int digits_;
};

}  // namespace wefm_common
