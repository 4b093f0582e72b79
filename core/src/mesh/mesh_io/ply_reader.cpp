// PLY, ASCII and binary (either byte order): `vertex` elements with x, y, z of any numeric type,
// kept as double, and `face` elements with a `vertex_indices` (or `vertex_index`) list, polygons
// fan-triangulated. Other elements and properties are read past and ignored.
#include <cstdint>
#include <cstring>
#include <sstream>

#include "file_buffer.hpp"
#include "readers.hpp"
#include "text_scan.hpp"
#include "wefm/core/sys/error.hpp"

namespace wefm::io {

namespace {

enum class Type { I8, U8, I16, U16, I32, U32, F32, F64 };

bool parse_type(const std::string& s, Type& t) {
  static const struct {
    const char* name;
    Type type;
  } names[] = {{"char", Type::I8},   {"int8", Type::I8},     {"uchar", Type::U8},   {"uint8", Type::U8},   {"short", Type::I16},
               {"int16", Type::I16}, {"ushort", Type::U16},  {"uint16", Type::U16}, {"int", Type::I32},    {"int32", Type::I32},
               {"uint", Type::U32},  {"uint32", Type::U32},  {"float", Type::F32},  {"float32", Type::F32}, {"double", Type::F64},
               {"float64", Type::F64}};
  for (const auto& n : names)
    if (s == n.name) {
      t = n.type;
      return true;
    }
  return false;
}

std::size_t size_of(Type t) {
  switch (t) {
    case Type::I8: case Type::U8: return 1;
    case Type::I16: case Type::U16: return 2;
    case Type::I32: case Type::U32: case Type::F32: return 4;
    case Type::F64: return 8;
  }
  return 0;
}

struct Property {
  std::string name;
  Type type = Type::F32;
  bool list = false;
  Type count_type = Type::U8;
};

struct Element {
  std::string name;
  long long count = 0;
  std::vector<Property> props;
};

enum class Format { Ascii, BinaryLittle, BinaryBig };

// Binary values: copy, swap when the file's byte order is not the machine's, convert.
class BinaryCursor {
 public:
  BinaryCursor(const char* p, const char* end, bool swap, const std::string& path) : p_(p), end_(end), swap_(swap), path_(path) {}
  double value(Type t) {
    const std::size_t n = size_of(t);
    if (static_cast<std::size_t>(end_ - p_) < n) fail(Errc::invalid_mesh, path_ + ": PLY data ends early (truncated file?)");
    unsigned char b[8];
    std::memcpy(b, p_, n);
    p_ += n;
    if (swap_)
      for (std::size_t i = 0; i < n / 2; ++i) std::swap(b[i], b[n - 1 - i]);
    switch (t) {
      case Type::I8: { std::int8_t v; std::memcpy(&v, b, 1); return v; }
      case Type::U8: { std::uint8_t v; std::memcpy(&v, b, 1); return v; }
      case Type::I16: { std::int16_t v; std::memcpy(&v, b, 2); return v; }
      case Type::U16: { std::uint16_t v; std::memcpy(&v, b, 2); return v; }
      case Type::I32: { std::int32_t v; std::memcpy(&v, b, 4); return v; }
      case Type::U32: { std::uint32_t v; std::memcpy(&v, b, 4); return v; }
      case Type::F32: { float v; std::memcpy(&v, b, 4); return v; }
      case Type::F64: { double v; std::memcpy(&v, b, 8); return v; }
    }
    return 0;
  }

 private:
  const char* p_;
  const char* end_;
  bool swap_;
  const std::string& path_;
};

// ASCII values: whitespace-separated numbers, records need not respect lines.
class AsciiCursor {
 public:
  AsciiCursor(const char* p, const char* end, const std::string& path) : p_(p), end_(end), path_(path) {}
  double value(Type) {
    while (p_ < end_ && (is_blank(*p_) || *p_ == '\n')) ++p_;
    double v = 0;
    const char* q = p_ < end_ ? scan_double(p_, end_, v) : nullptr;
    if (!q) fail(Errc::invalid_mesh, path_ + ": PLY data: expected a number" + (p_ < end_ ? "" : " (the file ends early)"));
    p_ = q;
    return v;
  }

 private:
  const char* p_;
  const char* end_;
  const std::string& path_;
};

template <class Cursor>
void read_body(Cursor& in, const std::vector<Element>& elements, ReadResult& r, const std::string& path) {
  std::vector<Index> poly;
  for (const Element& e : elements) {
    const bool is_vertex = e.name == "vertex", is_face = e.name == "face";
    int xyz[3] = {-1, -1, -1};
    int indices = -1;
    for (std::size_t k = 0; k < e.props.size(); ++k) {
      const Property& p = e.props[k];
      if (is_vertex && !p.list)
        for (int a = 0; a < 3; ++a)
          if (p.name == std::string(1, static_cast<char>('x' + a))) xyz[a] = static_cast<int>(k);
      if (is_face && p.list && (p.name == "vertex_indices" || p.name == "vertex_index")) indices = static_cast<int>(k);
    }
    if (is_vertex && (xyz[0] < 0 || xyz[1] < 0 || xyz[2] < 0)) fail(Errc::invalid_mesh, path + ": PLY vertex element has no x, y and z properties");
    if (is_face && indices < 0) fail(Errc::invalid_mesh, path + ": PLY face element has no vertex_indices list");
    if (is_vertex) r.mesh.vertices.resize(static_cast<std::size_t>(e.count));
    if (is_face) r.mesh.triangles.reserve(static_cast<std::size_t>(e.count));
    for (long long i = 0; i < e.count; ++i) {
      for (std::size_t k = 0; k < e.props.size(); ++k) {
        const Property& p = e.props[k];
        if (!p.list) {
          const double v = in.value(p.type);
          if (is_vertex)
            for (int a = 0; a < 3; ++a)
              if (xyz[a] == static_cast<int>(k)) r.mesh.vertices[static_cast<std::size_t>(i)][a] = v;
          continue;
        }
        const double n = in.value(p.count_type);
        if (!(n >= 0 && n <= 1e6)) fail(Errc::invalid_mesh, path + ": PLY " + e.name + " " + std::to_string(i) + ": bad list length");
        const bool keep = static_cast<int>(k) == indices;
        if (keep) poly.clear();
        for (long long m = 0; m < static_cast<long long>(n); ++m) {
          const double v = in.value(p.type);
          if (keep) poly.push_back(static_cast<Index>(v >= 0 && v <= 2147483647.0 ? v : -1));
        }
        if (keep) {
          if (poly.size() < 3) fail(Errc::invalid_mesh, path + ": PLY face " + std::to_string(i) + " has fewer than 3 vertices");
          add_fan(r.mesh.triangles, poly.data(), poly.size());
        }
      }
    }
  }
}

}  // namespace

ReadResult read_ply(const std::string& path) {
  const FileBuffer file(path);
  const char* p = file.begin();
  const char* const end = file.end();
  // Header: one keyword line at a time up to end_header.
  std::vector<Element> elements;
  Format format = Format::Ascii;
  bool have_format = false;
  std::size_t line = 0;
  auto header_error = [&](const std::string& what) { fail(Errc::invalid_mesh, path + ":" + std::to_string(line) + ": " + what); };
  while (true) {
    if (p >= end) fail(Errc::invalid_mesh, path + ": PLY header has no end_header");
    const char* nl = next_line(p, end);
    std::string text(p, static_cast<std::size_t>(nl - 1 - p));
    if (!text.empty() && text.back() == '\r') text.pop_back();
    ++line;
    p = nl;
    std::istringstream ls(text);
    std::string key;
    ls >> key;
    if (line == 1) {
      if (key != "ply") fail(Errc::invalid_mesh, path + ": not a PLY file (no 'ply' on the first line)");
      continue;
    }
    if (key == "end_header") break;
    if (key == "format") {
      std::string f;
      ls >> f;
      if (f == "ascii") format = Format::Ascii;
      else if (f == "binary_little_endian") format = Format::BinaryLittle;
      else if (f == "binary_big_endian") format = Format::BinaryBig;
      else header_error("unknown PLY format '" + f + "'");
      have_format = true;
    } else if (key == "element") {
      Element e;
      if (!(ls >> e.name >> e.count) || e.count < 0 || e.count > 0x7fffffffLL) header_error("bad element line");
      elements.push_back(e);
    } else if (key == "property") {
      if (elements.empty()) header_error("property before any element");
      Property pr;
      std::string t;
      ls >> t;
      if (t == "list") {
        std::string ct, it;
        ls >> ct >> it >> pr.name;
        pr.list = true;
        if (!parse_type(ct, pr.count_type) || !parse_type(it, pr.type)) header_error("unknown list property types '" + ct + " " + it + "'");
      } else {
        ls >> pr.name;
        if (!parse_type(t, pr.type)) header_error("unknown property type '" + t + "'");
      }
      elements.back().props.push_back(pr);
    } else if (!key.empty() && key != "comment" && key != "obj_info") {
      header_error("unknown PLY header keyword '" + key + "'");
    }
  }
  if (!have_format) fail(Errc::invalid_mesh, path + ": PLY header has no format line");
  // Counts are checked against the data before anything is allocated for them: a header that
  // promises 2^31 vertices in a 1 kB file is an error, not an attempt at a 48 GB allocation.
  {
    double least = 0;  // bytes the body needs at the very least
    for (const Element& e : elements) {
      double record = 0;
      for (const Property& pr : e.props)
        record += format == Format::Ascii ? 2.0 : static_cast<double>(pr.list ? size_of(pr.count_type) : size_of(pr.type));
      least += record * static_cast<double>(e.count);
    }
    if (least > static_cast<double>(end - p) + 1) fail(Errc::invalid_mesh, path + ": PLY data is shorter than the header's element counts need (truncated file?)");
  }
  ReadResult r;
  if (format == Format::Ascii) {
    AsciiCursor in(p, end, path);
    read_body(in, elements, r, path);
  } else {
    const std::uint16_t probe = 1;
    unsigned char first;
    std::memcpy(&first, &probe, 1);
    const bool little_machine = first == 1;
    BinaryCursor in(p, end, (format == Format::BinaryLittle) != little_machine, path);
    read_body(in, elements, r, path);
  }
  const std::size_t nv = r.mesh.vertices.size();
  for (std::size_t t = 0; t < r.mesh.triangles.size(); ++t)
    for (Index v : r.mesh.triangles[t])
      if (v < 0 || static_cast<std::size_t>(v) >= nv)
        fail(Errc::invalid_mesh, path + ": PLY face " + std::to_string(t) + " has a vertex index out of range [0, " + std::to_string(nv) + ")");
  if (r.mesh.triangles.empty()) fail(Errc::invalid_mesh, path + ": no faces found");
  return r;
}

}  // namespace wefm::io
