#pragma once
// Buffered file writer for large outputs (OBJ/SVG of a million triangles): one big buffer and
// std::to_chars, because iostream formatting per number dominates the run time at that size. The
// bytes go through OutputFile (output_file.hpp): the target is replaced whole on close, or not at all.
#include <charconv>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "exit_codes.hpp"
#include "output_file.hpp"
#include "stop.hpp"

namespace wefm_cli {

class TextOut {
 public:
  TextOut() : buf_(1 << 20) {}
  TextOut(const TextOut&) = delete;
  TextOut& operator=(const TextOut&) = delete;

  // False with error() when the file cannot be created.
  bool open(const std::string& path) { return file_.open(path); }
  // Flushes and puts the file in place; false with error() if anything failed (a full disk shows up
  // here at the latest) or a stop was requested, and then the previous file is left as it was.
  bool close() {
    flush();
    return file_.commit();
  }
  const std::string& error() const { return file_.error(); }
  // Exit code for a failed close: an I/O error, or the stop's own code (stop.hpp).
  int failure_code() const { return file_.stopped() ? stop_exit_code() : kExitIo; }

  void put(char c) {
    if (n_ == buf_.size()) flush();
    buf_[n_++] = c;
  }
  void put(std::string_view s) {
    if (n_ + s.size() > buf_.size()) flush();
    if (s.size() > buf_.size()) {
      write_raw(s.data(), s.size());
      return;
    }
    s.copy(buf_.data() + n_, s.size());
    n_ += s.size();
  }
  // Shortest text that reads back to the same double.
  void num(double v) {
    reserve(32);
    n_ = static_cast<size_t>(std::to_chars(buf_.data() + n_, buf_.data() + buf_.size(), v).ptr - buf_.data());
  }
  // printf's %.*g.
  void general(double v, int precision) {
    reserve(64);
    auto r = std::to_chars(buf_.data() + n_, buf_.data() + buf_.size(), v, std::chars_format::general, precision);
    if (r.ec != std::errc()) return put("0");
    n_ = static_cast<size_t>(r.ptr - buf_.data());
  }
  void fixed(double v, int precision) {
    reserve(64);
    auto r = std::to_chars(buf_.data() + n_, buf_.data() + buf_.size(), v, std::chars_format::fixed, precision);
    if (r.ec != std::errc()) return put("0");
    n_ = static_cast<size_t>(r.ptr - buf_.data());
  }
  void integer(int64_t v) {
    reserve(24);
    n_ = static_cast<size_t>(std::to_chars(buf_.data() + n_, buf_.data() + buf_.size(), v).ptr - buf_.data());
  }

 private:
  void reserve(size_t k) {
    if (n_ + k > buf_.size()) flush();
  }
  void flush() {
    if (n_) write_raw(buf_.data(), n_);
    n_ = 0;
  }
  void write_raw(const char* p, size_t k) { file_.write(p, k); }

  OutputFile file_;
  std::vector<char> buf_;
  size_t n_ = 0;
};

}  // namespace wefm_cli
