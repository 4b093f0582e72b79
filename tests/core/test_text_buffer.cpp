// TextBuffer and ObjLines (common/include/wefm/common/): the buffered text writer and the OBJ lines
// that the library's ObjWriter and the tool's mesh files share.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "wefm/common/obj_lines.hpp"
#include "wefm/common/text_buffer.hpp"

namespace {

// Keeps every write the buffer makes.
struct Recorder {
  std::string text;
  std::vector<std::size_t> writes;
  void write(const char* p, std::size_t n) {
    text.append(p, n);
    writes.push_back(n);
  }
};

// Takes `good` writes, then throws the way the library's AtomicFile does on a full disk.
struct Failing {
  int good = 0;
  std::string text;
  void write(const char* p, std::size_t n) {
    if (good-- <= 0) throw std::runtime_error("disk full");
    text.append(p, n);
  }
};

std::string printed(const char* format, int precision, double v) {
  char s[2048];
  std::snprintf(s, sizeof s, format, precision, v);
  return s;
}

std::string whole(wefm_common::TextBuffer<Recorder>& b) {
  b.flush();
  return b.sink().text;
}

}  // namespace

TEST_CASE("TextBuffer hands the sink blocks of at most the block size, in order") {
  wefm_common::TextBuffer<Recorder> b(64);
  std::string expected;
  for (int i = 0; i < 500; ++i) {
    b.put("line ");
    b.integer(i);
    b.put(' ');
    b.num(i * 0.25);
    b.put('\n');
    // i * 0.25 has at most two decimals: %.17g prints it as the shortest form does.
    expected += "line " + std::to_string(i) + " " + printed("%.*g", 17, i * 0.25) + "\n";
  }
  CHECK(b.sink().writes.size() > 10);  // nothing held back past a block
  CHECK(whole(b) == expected);
  for (std::size_t n : b.sink().writes) CHECK(n <= 64);
}

TEST_CASE("TextBuffer writes a piece longer than the block whole, after what it holds") {
  wefm_common::TextBuffer<Recorder> b(16);
  const std::string big(100, 'x');
  b.put("abc");
  b.put(big);
  b.put('!');
  CHECK(b.sink().writes == std::vector<std::size_t>{3, 100});
  CHECK(whole(b) == "abc" + big + "!");
}

TEST_CASE("TextBuffer numbers read back to the same value") {
  wefm_common::TextBuffer<Recorder> b(100);  // small: most numbers cross a block
  std::mt19937_64 rng(30);
  std::vector<double> values = {0.0, -0.0, 1.0, 0.1, 1.0 / 3.0, 1e-320, 5e-324, -1.7976931348623157e308, 123456789.125};
  while (values.size() < 5000) {
    const std::uint64_t bits = rng();
    double v;
    std::memcpy(&v, &bits, sizeof v);
    if (std::isfinite(v)) values.push_back(v);
  }
  for (double v : values) {
    b.num(v);
    b.put(' ');
    b.real(v, 17);
    b.put('\n');
  }
  const std::string text = whole(b);
  const char* p = text.c_str();
  for (double v : values) {
    char* end = nullptr;
    const double shortest = std::strtod(p, &end);
    REQUIRE(*end == ' ');
    const double g17 = std::strtod(end + 1, &end);
    REQUIRE(*end == '\n');
    p = end + 1;
    CHECK(std::memcmp(&shortest, &v, sizeof v) == 0);
    CHECK(std::memcmp(&g17, &v, sizeof v) == 0);
  }
  CHECK(*p == '\0');
}

TEST_CASE("TextBuffer integers, %g and %f equal printf's") {
  wefm_common::TextBuffer<Recorder> b(64);
  b.integer(std::numeric_limits<std::int64_t>::min());
  b.put(' ');
  b.integer(std::numeric_limits<std::int64_t>::max());
  CHECK(whole(b) == "-9223372036854775808 9223372036854775807");

  const double values[] = {0.0, 1.5, -2.0 / 3.0, 123456.789, 1e-7, 6.02e23, 1e300, -1.7976931348623157e308};
  const int precisions[] = {0, 1, 3, 6, 17, 40};
  for (double v : values)
    for (int p : precisions) {
      wefm_common::TextBuffer<Recorder> g(64), f(64);  // %f of 1e300 is longer than the block
      g.general(v, p);
      f.fixed(v, p);
      CHECK(whole(g) == printed("%.*g", p, v));
      CHECK(whole(f) == printed("%.*f", p, v));
    }
}

TEST_CASE("TextBuffer: a failing sink's error reaches the caller") {
  wefm_common::TextBuffer<Failing> b(8, Failing{1, {}});
  b.put("12345678");  // fills the block: no write yet
  b.put('9');         // the first block goes out
  CHECK(b.sink().text == "12345678");
  CHECK_THROWS_AS(b.put("abcdefgh"), std::runtime_error);            // the second one fails
  CHECK_THROWS_AS(b.put(std::string(20, 'y')), std::runtime_error);  // longer than the block: direct
  CHECK(b.sink().text == "12345678");
}

TEST_CASE("TextBuffer writes nothing when it is destroyed without flush()") {
  std::size_t writes = 0;
  struct Counting {
    std::size_t* writes;
    void write(const char*, std::size_t) { ++*writes; }
  };
  {
    wefm_common::TextBuffer<Counting> b(64, Counting{&writes});
    b.put("held back");
  }
  CHECK(writes == 0);
}

TEST_CASE("ObjLines writes the OBJ lines of both the library and the tool") {
  using Buffer = wefm_common::TextBuffer<Recorder>;
  Buffer b(32);
  wefm_common::ObjLines<Buffer> obj(b);
  obj.comment("two\nlines\r");
  obj.vertex(0.1, -2, 1e-300);
  obj.texture(0.5, 1.0 / 3.0);
  obj.group("face_1");
  const std::int32_t v[] = {0, 1, 2, 3}, t[] = {4, 5, 6, 7};
  obj.face(v, t, 4);
  obj.face(v, static_cast<const std::int32_t*>(nullptr), 3);
  CHECK(whole(b) ==
        "# two lines \n"
        "v 0.1 -2 1e-300\n"
        "vt 0.5 0.3333333333333333\n"
        "g face_1\n"
        "f 1/5 2/6 3/7 4/8\n"
        "f 1 2 3\n");

  Buffer b17(32);
  wefm_common::ObjLines<Buffer> obj17(b17, 17);
  obj17.vertex(0.1, -2, 0.5);
  CHECK(whole(b17) == "v 0.10000000000000001 -2 0.5\n");
}
