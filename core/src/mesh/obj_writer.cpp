#include "wefm/core/mesh/obj_writer.hpp"

#include <charconv>
#include <cstring>

namespace wefm {

namespace {

// Lines are gathered up to this many bytes before a write: per-number stdio or iostream formatting
// would dominate the time of a million-triangle file, and one write per line the system calls.
constexpr std::size_t kBlock = std::size_t{4} << 20;
// Room past a block for the line that crosses it: a vertex line is at most 3 x 24 characters, a
// face line is checked against it corner by corner.
constexpr std::size_t kSlack = 256;

}  // namespace

ObjWriter::ObjWriter(const std::string& path) : file_(path), buf_(kBlock + kSlack) {}

void ObjWriter::text(const char* s, std::size_t n) {
  if (n_ + n > buf_.size()) flush();
  if (n > buf_.size()) {
    file_.write(s, n);
    return;
  }
  std::memcpy(buf_.data() + n_, s, n);
  n_ += n;
}

template <class T>
void ObjWriter::number(T x) {
  n_ = static_cast<std::size_t>(std::to_chars(buf_.data() + n_, buf_.data() + buf_.size(), x).ptr - buf_.data());
}

void ObjWriter::end_line() {
  buf_[n_++] = '\n';
  if (n_ >= kBlock) flush();
}

void ObjWriter::flush() {
  file_.write(buf_.data(), n_);
  n_ = 0;
}

void ObjWriter::comment(const std::string& s) {
  text("# ", 2);
  text(s.data(), s.size());
  text("\n", 1);
  if (n_ >= kBlock) flush();
}

void ObjWriter::vertex(double x, double y, double z) {
  text("v ", 2);
  number(x);
  buf_[n_++] = ' ';
  number(y);
  buf_[n_++] = ' ';
  number(z);
  end_line();
}

void ObjWriter::texture(double u, double v) {
  text("vt ", 3);
  number(u);
  buf_[n_++] = ' ';
  number(v);
  end_line();
}

void ObjWriter::face(const Index* v, const Index* t, std::size_t corners) {
  text("f", 1);
  for (std::size_t k = 0; k < corners; ++k) {
    if (n_ + 32 > buf_.size()) flush();  // one corner: two 11-digit numbers and two separators
    buf_[n_++] = ' ';
    number(static_cast<long long>(v[k]) + 1);
    buf_[n_++] = '/';
    number(static_cast<long long>(t[k]) + 1);
  }
  end_line();
}

void ObjWriter::commit() {
  flush();
  file_.commit();
}

}  // namespace wefm
