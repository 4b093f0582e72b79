#pragma once
// Number scanning for the text mesh formats over a FileBuffer (which ends in a '\n' sentinel, so
// every loop here stops at a line end without an end-of-buffer test). Doubles go through
// std::from_chars (exact, locale-free, and without the locale and stream state that strtod and
// streams consult per number).
#include <charconv>
#include <cstdint>
#include <cstring>

namespace wefm::io {

inline bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r'; }
inline bool is_digit(char c) { return static_cast<unsigned>(c - '0') < 10u; }

// Skips spaces, tabs and carriage returns (not '\n').
inline const char* skip_blanks(const char* p) {
  while (is_blank(*p)) ++p;
  return p;
}

// Start of the next line (past the '\n'); `end` is the buffer end, whose sentinel is a '\n'.
inline const char* next_line(const char* p, const char* end) {
  const void* nl = std::memchr(p, '\n', static_cast<std::size_t>(end - p) + 1);
  return static_cast<const char*>(nl) + 1;
}

// A double at p (an optional '+' is accepted, as writers of some formats put one). Returns the
// character after it, or nullptr when there is no number at p.
inline const char* scan_double(const char* p, const char* end, double& value) {
  if (*p == '+' && (is_digit(p[1]) || p[1] == '.')) ++p;
  const auto r = std::from_chars(p, end, value);
  return r.ec == std::errc() ? r.ptr : nullptr;
}

// A decimal integer with optional '-' (and '+' when allow_plus). Returns nullptr when there is no
// digit, or when it has more than 18 digits (so the caller reports it instead of wrapping).
inline const char* scan_integer(const char* p, long long& value, bool allow_plus = false) {
  const bool negative = *p == '-';
  if (negative || (allow_plus && *p == '+')) ++p;
  const char* digits = p;
  unsigned long long v = 0;
  while (is_digit(*p) && p - digits < 18) v = v * 10 + static_cast<unsigned>(*p++ - '0');
  if (p == digits || is_digit(*p)) return nullptr;
  value = negative ? -static_cast<long long>(v) : static_cast<long long>(v);
  return p;
}

}  // namespace wefm::io
