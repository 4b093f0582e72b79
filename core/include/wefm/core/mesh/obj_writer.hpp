#pragma once
// The library's OBJ files (a flattened face's UV layout, a domain mesh): the OBJ lines of
// common/obj_lines, which the tool writes too, numbers as the shortest text that reads back to the
// same double, gathered by common/text_buffer and written through AtomicFile, so the file is
// replaced whole on commit() or not at all. Indices are given 0-based and written 1-based.
#include <cstddef>
#include <string>

#include "wefm/common/obj_lines.hpp"
#include "wefm/common/text_buffer.hpp"
#include "wefm/core/sys/atomic_file.hpp"
#include "wefm/core/sys/types.hpp"

namespace wefm {

class ObjWriter {
 public:
  // Throws Error(io) naming the file when it cannot be created.
  explicit ObjWriter(const std::string& path);

  void comment(const std::string& text) { lines_.comment(text); }                        // "# text"
  void vertex(double x, double y, double z) { lines_.vertex(x, y, z); }                  // "v x y z"
  void texture(double u, double v) { lines_.texture(u, v); }                             // "vt u v"
  // "f v1/t1 v2/t2 ...": corner k is vertex v[k] with texture vertex t[k] (0-based).
  void face(const Index* v, const Index* t, std::size_t corners) { lines_.face(v, t, corners); }

  // Writes what is left and puts the file in place; throws Error(io), the previous file kept.
  void commit();

 private:
  using Buffer = wefm_common::TextBuffer<AtomicFile>;
  Buffer out_;  // a write error throws from whichever call fills a block
  wefm_common::ObjLines<Buffer> lines_;
};

}  // namespace wefm
