#pragma once
// Buffered file writer for large outputs (OBJ/SVG of a million triangles): one big buffer and
// std::to_chars, because iostream formatting per number dominates the run time at that size.
#include <charconv>
#include <cstdint>
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

namespace wefm_cli {

class TextOut {
 public:
  TextOut() : buf_(1 << 20) {}
  TextOut(const TextOut&) = delete;
  TextOut& operator=(const TextOut&) = delete;
  ~TextOut() { close(); }

  // False with errno set when the file cannot be created.
  bool open(const std::string& path) {
    file_ = std::fopen(path.c_str(), "wb");
    return file_ != nullptr;
  }
  // Flushes and closes; false if any write failed (disk full shows up here, not as a short file).
  bool close() {
    if (!file_) return !failed_;
    flush();
    if (std::fclose(file_) != 0) failed_ = true;
    file_ = nullptr;
    return !failed_;
  }

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
  void write_raw(const char* p, size_t k) {
    if (!file_ || std::fwrite(p, 1, k, file_) != k) failed_ = true;
  }

  std::FILE* file_ = nullptr;
  std::vector<char> buf_;
  size_t n_ = 0;
  bool failed_ = false;
};

}  // namespace wefm_cli
