#pragma once
// The splitmix64 finaliser: spreads every bit of a 64-bit value over all of the result's, cheaply.
// A hash of bit patterns (vertex merging) and, fed a counter, a fixed-seed random stream (the
// triangulation's insertion order).
#include <cstdint>

namespace wefm {

inline std::uint64_t mix64(std::uint64_t h) {
  h ^= h >> 30;
  h *= 0xbf58476d1ce4e5b9ULL;
  h ^= h >> 27;
  h *= 0x94d049bb133111ebULL;
  return h ^ (h >> 31);
}

}  // namespace wefm
