#pragma once
// Buffered text for the project's large outputs (OBJ, MSH, VTK, VTU, PLY, SVG of a million
// triangles), in the library and in the tool alike: pieces and numbers are gathered in one block
// and handed to the sink a block at a time, numbers formatted with std::to_chars (per-number stdio
// or iostream formatting would dominate the writing time at that size, and a write per line the
// system calls).
//
// The sink is the caller's: any type with write(const char* data, std::size_t size), owned by the
// buffer and reached through sink(). What a failed write does is the sink's own policy: the
// library's AtomicFile throws, the tool's OutputFile records the error and ignores what follows;
// the buffer neither catches nor checks. Nothing is written on destruction: a buffer abandoned
// without flush() leaves its last block unwritten, as the sink's own discard expects.
#include <algorithm>
#include <charconv>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

namespace wefm_common {

template <class Sink>
class TextBuffer {
 public:
  // Writes reach the sink in pieces of at most `block` bytes (a single put() longer than that goes
  // to it whole); the sink is constructed from `sink_args`, before the block is allocated.
  template <class... SinkArgs>
  explicit TextBuffer(std::size_t block, SinkArgs&&... sink_args)
      : sink_(std::forward<SinkArgs>(sink_args)...), buf_(std::max<std::size_t>(block, 1)) {}
  TextBuffer(const TextBuffer&) = delete;
  TextBuffer& operator=(const TextBuffer&) = delete;

  Sink& sink() { return sink_; }
  const Sink& sink() const { return sink_; }

  void put(char c) {
    if (n_ == buf_.size()) flush();
    buf_[n_++] = c;
  }
  void put(std::string_view s) {
    if (n_ + s.size() > buf_.size()) flush();
    if (s.size() > buf_.size()) {
      sink_.write(s.data(), s.size());
      return;
    }
    if (!s.empty()) std::memcpy(buf_.data() + n_, s.data(), s.size());
    n_ += s.size();
  }
  // The shortest text that reads back to the same double.
  void num(double v) {
    format(kNumberRoom, [v](char* first, char* last) { return std::to_chars(first, last, v); });
  }
  // printf's %.*g.
  void general(double v, int precision) {
    format(kNumberRoom + digits(precision),
           [=](char* first, char* last) { return std::to_chars(first, last, v, std::chars_format::general, precision); });
  }
  // printf's %.*f.
  void fixed(double v, int precision) {
    format(kNumberRoom + kIntegerDigits + digits(precision),
           [=](char* first, char* last) { return std::to_chars(first, last, v, std::chars_format::fixed, precision); });
  }
  void integer(std::int64_t v) {
    format(kNumberRoom, [v](char* first, char* last) { return std::to_chars(first, last, v); });
  }
  // A number style chosen once by the caller: `digits` 0 is num(v), otherwise general(v, digits).
  void real(double v, int digits) {
    if (digits > 0) general(v, digits);
    else num(v);
  }

  // Hands what is gathered to the sink.
  void flush() {
    const std::size_t n = n_;
    n_ = 0;
    if (n) sink_.write(buf_.data(), n);
  }

 private:
  // Room for a sign, the shortest double (at most 24 characters), a 64-bit integer (20), the
  // point and exponent of a formatted number.
  static constexpr std::size_t kNumberRoom = 32;
  // The digits of the largest double before the point in fixed notation.
  static constexpr std::size_t kIntegerDigits = 309;
  // printf takes a negative precision as 6.
  static std::size_t digits(int precision) { return static_cast<std::size_t>(precision < 0 ? 6 : precision); }

  // Formats in place after making `room` bytes free, `room` being at least the longest text `to`
  // can produce, so to_chars cannot run out of space; a number longer than the whole block (a
  // huge precision) is formatted aside and put whole.
  template <class To>
  void format(std::size_t room, To to) {
    if (room > buf_.size()) {
      std::vector<char> aside(room);
      const std::to_chars_result r = to(aside.data(), aside.data() + room);
      put(std::string_view(aside.data(), static_cast<std::size_t>(r.ptr - aside.data())));
      return;
    }
    if (n_ + room > buf_.size()) flush();
    n_ = static_cast<std::size_t>(to(buf_.data() + n_, buf_.data() + buf_.size()).ptr - buf_.data());
  }

  Sink sink_;
  std::vector<char> buf_;
  std::size_t n_ = 0;
};

}  // namespace wefm_common
