#pragma once
// Reads typed values from fuzzer bytes; past the end everything reads as zero. Used instead of
// libFuzzer's FuzzedDataProvider so the same targets build with GCC as corpus replay programs.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>

namespace wefm_fuzz {

class Input {
 public:
  Input(const uint8_t* data, size_t size) : p_(data), n_(size) {}
  bool empty() const { return i_ >= n_; }
  uint8_t u8() { return i_ < n_ ? p_[i_++] : 0; }
  uint32_t u32() {
    uint32_t v = 0;
    for (int k = 0; k < 4; ++k) v |= static_cast<uint32_t>(u8()) << (8 * k);
    return v;
  }
  int32_t i32() { return static_cast<int32_t>(u32()); }
  uint64_t u64() { return u32() | (static_cast<uint64_t>(u32()) << 32); }
  double raw_double() {
    const uint64_t b = u64();
    double d;
    std::memcpy(&d, &b, sizeof d);
    return d;
  }
  // Mostly ordinary numbers, sometimes the values that break arithmetic.
  double number() {
    const uint8_t k = u8();
    switch (k % 16) {
      case 0: return std::numeric_limits<double>::quiet_NaN();
      case 1: return std::numeric_limits<double>::infinity();
      case 2: return -std::numeric_limits<double>::infinity();
      case 3: return raw_double();
      case 4: return 1e300 * (k & 16 ? -1 : 1);
      case 5: return 1e-300;
      case 6: return 0.0;
      default: return (static_cast<int>(u8()) - 128) / 16.0;
    }
  }
  // A small index around [lo, hi), occasionally a huge or negative one.
  int32_t index(int32_t lo, int32_t hi) {
    const uint8_t k = u8();
    if (k == 255) return i32();
    if (k == 254) return -1;
    const int64_t span = static_cast<int64_t>(hi) - lo + 2;
    return static_cast<int32_t>(lo - 1 + static_cast<int64_t>(k) % (span > 0 ? span : 1));
  }

 private:
  const uint8_t* p_;
  size_t n_, i_ = 0;
};

// Invariant violations abort so the fuzzer records the input.
[[noreturn]] inline void violated(const char* what, const char* detail) {
  std::fprintf(stderr, "wefm fuzz invariant violated: %s: %s\n", what, detail ? detail : "");
  std::abort();
}

}  // namespace wefm_fuzz
