#include "cad_model_wire.hpp"

#include <cstdint>
#include <cstring>
#include <type_traits>

namespace wefm_cad {

namespace {

constexpr uint64_t kMagic = 0x77656d2d6361642dULL;  // changes with the layout below

class Writer {
 public:
  template <class T>
  void pod(T v) {
    static_assert(std::is_trivially_copyable_v<T>);
    out_.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  void str(const std::string& s) {
    pod<uint64_t>(s.size());
    out_ += s;
  }
  template <class T>
  void vec(const std::vector<T>& v) {
    pod<uint64_t>(v.size());
    if (!v.empty()) out_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
  std::string take() { return std::move(out_); }

 private:
  std::string out_;
};

class Reader {
 public:
  explicit Reader(std::string_view in) : in_(in) {}
  template <class T>
  bool pod(T& v) {
    if (in_.size() < sizeof v) return false;
    std::memcpy(&v, in_.data(), sizeof v);
    in_.remove_prefix(sizeof v);
    return true;
  }
  bool count(uint64_t& n, size_t item_size) { return pod(n) && n <= in_.size() / item_size; }
  bool str(std::string& s) {
    uint64_t n = 0;
    if (!count(n, 1)) return false;
    s.assign(in_.data(), n);
    in_.remove_prefix(n);
    return true;
  }
  template <class T>
  bool vec(std::vector<T>& v) {
    uint64_t n = 0;
    if (!count(n, sizeof(T))) return false;
    v.resize(n);
    if (n) std::memcpy(v.data(), in_.data(), n * sizeof(T));  // an empty vector's data() may be null
    in_.remove_prefix(n * sizeof(T));
    return true;
  }
  bool done() const { return in_.empty(); }

 private:
  std::string_view in_;
};

void put_face(Writer& w, const CadFace& f) {
  w.pod<int32_t>(f.index);
  w.str(f.surface_type);
  w.vec(f.xyz);
  w.vec(f.triangles);
  w.pod<uint64_t>(f.edges.size());
  for (const CadEdge& e : f.edges) {
    w.pod<int64_t>(e.id);
    w.vec(e.vertices);
    w.pod<uint8_t>(e.seam);
    w.pod<uint8_t>(e.degenerated);
    w.str(e.curve_type);
  }
  w.pod<uint64_t>(f.loops.size());
  for (const auto& loop : f.loops) {
    w.pod<uint64_t>(loop.size());
    for (const CadEdgeUse& u : loop) {
      w.pod<int32_t>(u.edge);
      w.pod<uint8_t>(u.reversed);
    }
  }
  w.pod<int32_t>(f.outer_loop);
  w.pod<int64_t>(f.dropped_triangles);
  w.pod<uint8_t>(f.triangulation_kept);
  w.str(f.error);
}

bool get_flag(Reader& r, bool& b) {
  uint8_t v = 0;
  if (!r.pod(v) || v > 1) return false;
  b = v != 0;
  return true;
}

bool get_edge(Reader& r, CadEdge& e) {
  int64_t id = 0;
  if (!r.pod(id) || !r.vec(e.vertices) || !get_flag(r, e.seam) || !get_flag(r, e.degenerated) || !r.str(e.curve_type))
    return false;
  e.id = id;
  return true;
}

bool get_face(Reader& r, CadFace& f) {
  int32_t index = 0, outer = 0;
  uint64_t n = 0;
  if (!r.pod(index) || !r.str(f.surface_type) || !r.vec(f.xyz) || !r.vec(f.triangles) || !r.count(n, 8)) return false;
  f.index = index;
  f.edges.resize(n);
  for (CadEdge& e : f.edges)
    if (!get_edge(r, e)) return false;
  if (!r.count(n, 8)) return false;
  f.loops.resize(n);
  for (auto& loop : f.loops) {
    uint64_t m = 0;
    if (!r.count(m, 5)) return false;
    loop.resize(m);
    for (CadEdgeUse& u : loop)
      if (!r.pod(u.edge) || !get_flag(r, u.reversed)) return false;
  }
  int64_t dropped = 0;
  if (!r.pod(outer) || !r.pod(dropped) || !get_flag(r, f.triangulation_kept) || !r.str(f.error)) return false;
  f.outer_loop = outer;
  f.dropped_triangles = dropped;
  return true;
}

}  // namespace

std::string encode_cad_model(const CadModel& m) {
  Writer w;
  w.pod(kMagic);
  w.str(m.path);
  w.str(m.format);
  for (double v : {m.bbox_diagonal, m.linear_deflection, m.time_read, m.time_mesh, m.time_extract}) w.pod(v);
  w.pod<int64_t>(m.edge_count);
  w.pod<uint64_t>(m.faces.size());
  for (const CadFace& f : m.faces) put_face(w, f);
  return w.take();
}

bool decode_cad_model(std::string_view bytes, CadModel& m) {
  m = CadModel{};
  Reader r(bytes);
  uint64_t magic = 0, n = 0;
  int64_t edges = 0;
  if (!r.pod(magic) || magic != kMagic || !r.str(m.path) || !r.str(m.format)) return false;
  for (double* v : {&m.bbox_diagonal, &m.linear_deflection, &m.time_read, &m.time_mesh, &m.time_extract})
    if (!r.pod(*v)) return false;
  if (!r.pod(edges) || !r.count(n, 8)) return false;
  m.edge_count = edges;
  m.faces.resize(n);
  for (CadFace& f : m.faces)
    if (!get_face(r, f)) return false;
  return r.done();
}

}  // namespace wefm_cad
