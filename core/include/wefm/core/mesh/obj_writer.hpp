#pragma once
// The library's one OBJ writer, for every file it writes (a flattened face's UV layout, a domain
// mesh): numbers as the shortest text that reads back to the same double, lines gathered in a
// large buffer and written in blocks, the file replaced whole on commit() or not at all
// (AtomicFile). Indices are given 0-based and written 1-based, as OBJ counts.
#include <cstddef>
#include <string>
#include <vector>

#include "wefm/core/sys/atomic_file.hpp"
#include "wefm/core/sys/types.hpp"

namespace wefm {

class ObjWriter {
 public:
  // Throws Error(io) naming the file when it cannot be created.
  explicit ObjWriter(const std::string& path);

  void comment(const std::string& text);         // "# text"
  void vertex(double x, double y, double z);     // "v x y z"
  void texture(double u, double v);              // "vt u v"
  // "f v1/t1 v2/t2 ...": corner k is vertex v[k] with texture vertex t[k] (0-based).
  void face(const Index* v, const Index* t, std::size_t corners);

  // Writes what is left and puts the file in place; throws Error(io), the previous file kept.
  void commit();

 private:
  void text(const char* s, std::size_t n);
  template <class T>
  void number(T x);
  void end_line();
  void flush();

  AtomicFile file_;
  std::vector<char> buf_;
  std::size_t n_ = 0;
};

}  // namespace wefm
