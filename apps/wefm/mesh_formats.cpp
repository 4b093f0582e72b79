#include "mesh_formats.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <map>

#include "exit_codes.hpp"
#include "text_out.hpp"
#include "wefm/common/element_corners.hpp"
#include "wefm/common/obj_lines.hpp"

namespace wefm_cli {

namespace {

struct FormatName {
  MeshFormat format;
  const char* name;
  const char* extension;
};

constexpr std::array<FormatName, 5> kFormats = {{{MeshFormat::obj, "obj", ".obj"},
                                                 {MeshFormat::msh, "msh", ".msh"},
                                                 {MeshFormat::vtk, "vtk", ".vtk"},
                                                 {MeshFormat::vtu, "vtu", ".vtu"},
                                                 {MeshFormat::ply, "ply", ".ply"}}};

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// A comment line may not end the comment early or break the file's syntax.
std::string one_line(const std::string& s) {
  std::string out = s;
  for (char& c : out) c = c == '\n' || c == '\r' ? ' ' : c;
  return out;
}

// The mesh as the writers read it: checked, groups filled in, one UV per point where needed.
class Prepared {
 public:
  Prepared(const MeshDescription& m, bool one_uv_per_point) : m_(m) {
    if (m_.groups.empty()) m_.groups.push_back({1, "face_1"});
    if (one_uv_per_point && !m.corner_uv.empty() && m.corner_uv.size == m.elements.size) split_at_seams();
  }
  const MeshDescription& mesh() const { return m_; }
  size_t points() const { return m_.xyz.size / 3; }
  size_t elements() const { return m_.elements.size / npe(); }
  size_t npe() const { return static_cast<size_t>(m_.nodes_per_element); }
  // Corners of element e: a quad-dominant mesh's triangle is four nodes, the last -1.
  size_t corners(size_t e) const { return wefm_common::element_corners(m_.elements.data + e * npe(), m_.nodes_per_element); }
  bool has_uv() const { return !m_.uv.empty(); }
  int group_of_element(size_t e) const { return m_.element_group.empty() ? m_.groups[0].tag : m_.element_group[e]; }
  // MSH: the entity a point is listed under.
  std::vector<int> point_groups() const;

  // An inconsistent description is the tool's own bug; refuse it rather than write a broken file.
  bool consistent(bool uv_per_point, std::string& why) const;

 private:
  // A point per UV: its position is the one of the vertex whose corner uses that UV.
  void split_at_seams() {
    const size_t nu = m_.uv.size / 2;
    xyz_.assign(3 * nu, 0.0);
    for (size_t c = 0; c < m_.corner_uv.size; ++c) {
      const size_t u = static_cast<size_t>(m_.corner_uv[c]), p = static_cast<size_t>(m_.elements[c]);
      if (u >= nu || 3 * p + 2 >= m_.xyz.size) continue;  // left to consistent()
      std::copy(m_.xyz.data + 3 * p, m_.xyz.data + 3 * p + 3, xyz_.begin() + static_cast<std::ptrdiff_t>(3 * u));
    }
    m_.xyz = xyz_;
    m_.elements = m_.corner_uv;
    m_.corner_uv = {};
    m_.point_group = {};
  }

  MeshDescription m_;
  std::vector<double> xyz_;  // owned when split
};

std::vector<int> Prepared::point_groups() const {
  if (!m_.point_group.empty()) return std::vector<int>(m_.point_group.data, m_.point_group.data + m_.point_group.size);
  std::vector<int> g(points(), 0);
  std::vector<char> seen(points(), 0);
  for (size_t e = 0; e < elements(); ++e)
    for (size_t k = 0; k < corners(e); ++k) {
      const size_t p = static_cast<size_t>(m_.elements[e * npe() + k]);
      if (!seen[p]) g[p] = group_of_element(e), seen[p] = 1;
    }
  for (size_t p = 0; p < g.size(); ++p)
    if (!seen[p]) g[p] = m_.groups[0].tag;
  return g;
}

bool Prepared::consistent(bool uv_per_point, std::string& why) const {
  const size_t n = points(), nu = m_.uv.size / 2;
  if (m_.nodes_per_element != 3 && m_.nodes_per_element != 4) why = "elements of neither 3 nor 4 nodes";
  else if (m_.xyz.size % 3 || m_.uv.size % 2 || m_.elements.size % npe()) why = "array sizes";
  else if (!m_.element_group.empty() && m_.element_group.size != elements()) why = "a group per element";
  else if (!m_.point_group.empty() && m_.point_group.size != n) why = "a group per point";
  else if (!m_.corner_uv.empty() && m_.corner_uv.size != m_.elements.size) why = "a UV per corner";
  else if (has_uv() && m_.corner_uv.empty() && nu < n) why = "a UV per point";
  else if (uv_per_point && has_uv() && nu != n) why = "one UV per point";
  for (size_t i = 0; why.empty() && i < m_.elements.size; ++i) {
    if (npe() == 4 && i % 4 == 3 && m_.elements[i] == -1) continue;  // a triangle among quads
    if (m_.elements[i] < 0 || static_cast<size_t>(m_.elements[i]) >= n) why = "an element node out of range";
  }
  for (size_t i = 0; why.empty() && i < m_.corner_uv.size; ++i) {
    if (npe() == 4 && i % 4 == 3 && m_.elements[i] == -1) continue;  // a triangle among quads
    if (m_.corner_uv[i] < 0 || static_cast<size_t>(m_.corner_uv[i]) >= nu) why = "a corner UV out of range";
  }
  return why.empty();
}

// TextOut with the description's number style (`digits` as TextOut::real takes it).
class Writer {
 public:
  Writer(TextOut& out, int digits) : out_(out), digits_(digits) {}
  Writer& num(double v) {
    out_.real(v, digits_);
    return *this;
  }
  Writer& nums(const double* v, size_t n, char sep = ' ') {
    for (size_t i = 0; i < n; ++i) {
      if (i) out_.put(sep);
      num(v[i]);
    }
    return *this;
  }
  Writer& put(std::string_view s) {
    out_.put(s);
    return *this;
  }
  Writer& put(char c) {
    out_.put(c);
    return *this;
  }
  Writer& integer(int64_t v) {
    out_.integer(v);
    return *this;
  }

 private:
  TextOut& out_;
  int digits_;
};

// The OBJ lines of common/obj_lines, which the library's OBJ files use too: a `g NAME` line where
// the group changes (obj_groups), "f v/vt" with UVs, "f v" without.
void write_obj(TextOut& out, int digits, const Prepared& p) {
  const MeshDescription& m = p.mesh();
  wefm_common::ObjLines<TextOut> obj(out, digits);
  for (const std::string& c : m.comments) obj.comment(c);
  for (size_t i = 0; i < p.points(); ++i) obj.vertex(m.xyz[3 * i], m.xyz[3 * i + 1], m.xyz[3 * i + 2]);
  for (size_t i = 0; i + 1 < m.uv.size; i += 2) obj.texture(m.uv[i], m.uv[i + 1]);
  std::map<int, std::string> names;
  for (const MeshGroup& g : m.groups) names[g.tag] = g.name;
  bool first = true;
  int current = 0;
  for (size_t e = 0; e < p.elements(); ++e) {
    if (m.obj_groups && (first || p.group_of_element(e) != current)) {
      current = p.group_of_element(e);
      obj.group(names[current]);
    }
    first = false;
    const int32_t* v = m.elements.data + e * p.npe();
    const int32_t* t = !p.has_uv() ? nullptr : m.corner_uv.empty() ? v : m.corner_uv.data + e * p.npe();
    obj.face(v, t, p.corners(e));
  }
}

// $Nodes and $Entities list points under the entity of their group; $Elements per group.
void write_msh(Writer& w, const Prepared& p) {
  const MeshDescription& m = p.mesh();
  w.put("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n").integer(static_cast<int64_t>(m.groups.size())).put('\n');
  for (const MeshGroup& g : m.groups) {
    std::string name = one_line(g.name);
    name.erase(std::remove(name.begin(), name.end(), '"'), name.end());
    w.put("2 ").integer(g.tag).put(" \"").put(name).put("\"\n");
  }
  const std::vector<int> point_group = p.point_groups();
  std::map<int, std::vector<size_t>> points_of;
  for (size_t v = 0; v < point_group.size(); ++v) points_of[point_group[v]].push_back(v);
  w.put("$EndPhysicalNames\n$Entities\n0 0 ").integer(static_cast<int64_t>(m.groups.size())).put(" 0\n");
  for (const MeshGroup& g : m.groups) {
    std::array<double, 6> box{0, 0, 0, 0, 0, 0};
    if (points_of.count(g.tag)) {
      box = {1e300, 1e300, 1e300, -1e300, -1e300, -1e300};
      for (size_t v : points_of.at(g.tag))
        for (size_t c = 0; c < 3; ++c) box[c] = std::min(box[c], m.xyz[3 * v + c]), box[c + 3] = std::max(box[c + 3], m.xyz[3 * v + c]);
    }
    w.integer(g.tag).put(' ').nums(box.data(), 6).put(" 1 ").integer(g.tag).put(" 0\n");
  }
  const int64_t n = static_cast<int64_t>(p.points()), ne = static_cast<int64_t>(p.elements());
  w.put("$EndEntities\n$Nodes\n").integer(static_cast<int64_t>(points_of.size())).put(' ').integer(n).put(" 1 ").integer(n).put('\n');
  for (const auto& [tag, vs] : points_of) {
    w.put("2 ").integer(tag).put(" 0 ").integer(static_cast<int64_t>(vs.size())).put('\n');
    for (size_t v : vs) w.integer(static_cast<int64_t>(v) + 1).put('\n');
    for (size_t v : vs) w.nums(&m.xyz[3 * v], 3).put('\n');
  }
  // A block per group and element type (a quad-dominant mesh has triangles and quads).
  std::map<std::pair<int, size_t>, std::vector<size_t>> elements_of;
  for (size_t e = 0; e < p.elements(); ++e) elements_of[{p.group_of_element(e), p.corners(e)}].push_back(e);
  w.put("$EndNodes\n$Elements\n").integer(static_cast<int64_t>(elements_of.size())).put(' ').integer(ne).put(" 1 ").integer(ne).put('\n');
  for (const auto& [block, es] : elements_of) {
    const auto [tag, corners] = block;
    w.put("2 ").integer(tag).put(corners == 4 ? " 3 " : " 2 ").integer(static_cast<int64_t>(es.size())).put('\n');
    for (size_t e : es) {
      w.integer(static_cast<int64_t>(e) + 1);
      for (size_t k = 0; k < corners; ++k) w.put(' ').integer(int64_t{m.elements[e * p.npe() + k]} + 1);
      w.put('\n');
    }
  }
  w.put("$EndElements\n");
  if (!p.has_uv()) return;
  w.put("$NodeData\n1\n\"uv\"\n1\n0\n3\n0\n3\n").integer(n).put('\n');
  for (size_t v = 0; v < p.points(); ++v) w.integer(static_cast<int64_t>(v) + 1).put(' ').nums(&m.uv[2 * v], 2).put(" 0\n");
  w.put("$EndNodeData\n");
}

int vtk_cell_type(const Prepared& p, size_t e) { return p.corners(e) == 4 ? 9 : 5; }

void write_vtk(Writer& w, const Prepared& p) {
  const MeshDescription& m = p.mesh();
  std::string title = m.comments.empty() ? "wefm mesh" : one_line(m.comments[0]);
  if (title.size() > 255) title.resize(255);
  const int64_t n = static_cast<int64_t>(p.points()), ne = static_cast<int64_t>(p.elements());
  w.put("# vtk DataFile Version 3.0\n").put(title).put("\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS ").integer(n).put(" double\n");
  for (size_t v = 0; v < p.points(); ++v) w.nums(&m.xyz[3 * v], 3).put('\n');
  int64_t cell_list = 0;
  for (size_t e = 0; e < p.elements(); ++e) cell_list += static_cast<int64_t>(p.corners(e) + 1);
  w.put("CELLS ").integer(ne).put(' ').integer(cell_list).put('\n');
  for (size_t e = 0; e < p.elements(); ++e) {
    w.integer(static_cast<int64_t>(p.corners(e)));
    for (size_t k = 0; k < p.corners(e); ++k) w.put(' ').integer(m.elements[e * p.npe() + k]);
    w.put('\n');
  }
  w.put("CELL_TYPES ").integer(ne).put('\n');
  for (size_t e = 0; e < p.elements(); ++e) w.integer(vtk_cell_type(p, e)).put('\n');
  if (p.has_uv()) {
    w.put("POINT_DATA ").integer(n).put("\nFIELD FieldData 1\nuv 2 ").integer(n).put(" double\n");
    for (size_t v = 0; v < p.points(); ++v) w.nums(&m.uv[2 * v], 2).put('\n');
  }
  w.put("CELL_DATA ").integer(ne).put("\nSCALARS face_id int 1\nLOOKUP_TABLE default\n");
  for (size_t e = 0; e < p.elements(); ++e) w.integer(p.group_of_element(e)).put('\n');
}

void write_vtu(Writer& w, const Prepared& p) {
  const MeshDescription& m = p.mesh();
  w.put("<?xml version=\"1.0\"?>\n");
  for (const std::string& c : m.comments) {
    std::string text = one_line(c);
    for (size_t k; (k = text.find("--")) != std::string::npos;) text[k] = '_';  // "--" ends an XML comment
    w.put("<!-- ").put(text).put(" -->\n");
  }
  w.put("<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n<UnstructuredGrid>\n<Piece NumberOfPoints=\"")
      .integer(static_cast<int64_t>(p.points()))
      .put("\" NumberOfCells=\"")
      .integer(static_cast<int64_t>(p.elements()))
      .put("\">\n<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n");
  for (size_t v = 0; v < p.points(); ++v) w.nums(&m.xyz[3 * v], 3).put('\n');
  w.put("</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n");
  for (size_t e = 0; e < p.elements(); ++e) {
    for (size_t k = 0; k < p.corners(e); ++k) w.put(k ? " " : "").integer(m.elements[e * p.npe() + k]);
    w.put('\n');
  }
  w.put("</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n");
  int64_t offset = 0;
  for (size_t e = 0; e < p.elements(); ++e) w.integer(offset += static_cast<int64_t>(p.corners(e))).put('\n');
  w.put("</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n");
  for (size_t e = 0; e < p.elements(); ++e) w.integer(vtk_cell_type(p, e)).put('\n');
  w.put("</DataArray>\n</Cells>\n");
  if (p.has_uv()) {
    w.put("<PointData>\n<DataArray type=\"Float64\" Name=\"uv\" NumberOfComponents=\"2\" format=\"ascii\">\n");
    for (size_t v = 0; v < p.points(); ++v) w.nums(&m.uv[2 * v], 2).put('\n');
    w.put("</DataArray>\n</PointData>\n");
  }
  w.put("<CellData>\n<DataArray type=\"Int32\" Name=\"face_id\" format=\"ascii\">\n");
  for (size_t e = 0; e < p.elements(); ++e) w.integer(p.group_of_element(e)).put('\n');
  w.put("</DataArray>\n</CellData>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n");
}

void write_ply(Writer& w, const Prepared& p) {
  const MeshDescription& m = p.mesh();
  w.put("ply\nformat ascii 1.0\n");
  for (const std::string& c : m.comments) w.put("comment ").put(one_line(c)).put('\n');
  for (const MeshGroup& g : m.groups) w.put("comment face_id ").integer(g.tag).put(' ').put(one_line(g.name)).put('\n');
  w.put("element vertex ").integer(static_cast<int64_t>(p.points())).put("\nproperty double x\nproperty double y\nproperty double z\n");
  if (p.has_uv()) w.put("property double u\nproperty double v\n");
  w.put("element face ").integer(static_cast<int64_t>(p.elements()))
      .put("\nproperty list uchar int vertex_indices\nproperty int face_id\nend_header\n");
  for (size_t v = 0; v < p.points(); ++v) {
    w.nums(&m.xyz[3 * v], 3);
    if (p.has_uv()) w.put(' ').nums(&m.uv[2 * v], 2);
    w.put('\n');
  }
  for (size_t e = 0; e < p.elements(); ++e) {
    w.integer(static_cast<int64_t>(p.corners(e)));
    for (size_t k = 0; k < p.corners(e); ++k) w.put(' ').integer(m.elements[e * p.npe() + k]);
    w.put(' ').integer(p.group_of_element(e)).put('\n');
  }
}

}  // namespace

bool parse_mesh_format(const std::string& name, MeshFormat& format, std::string& error) {
  for (const FormatName& f : kFormats)
    if (lower(name) == f.name) {
      format = f.format;
      return true;
    }
  error = "unknown mesh format '" + name + "' (expected " + mesh_format_names() + ")";
  return false;
}

bool mesh_format_of(const std::string& path, MeshFormat& format, std::string& error) {
  const size_t slash = path.rfind('/'), dot = path.rfind('.');
  const bool has_extension = dot != std::string::npos && (slash == std::string::npos || dot > slash + 1);
  if (!has_extension) {
    format = MeshFormat::obj;
    return true;
  }
  const std::string ext = lower(path.substr(dot));
  for (const FormatName& f : kFormats)
    if (ext == f.extension) {
      format = f.format;
      return true;
    }
  error = path + ": unknown mesh file extension '" + path.substr(dot) + "' (expected .obj, .msh, .vtk, .vtu or .ply)";
  return false;
}

const char* mesh_format_extension(MeshFormat format) {
  for (const FormatName& f : kFormats)
    if (f.format == format) return f.extension;
  return ".obj";
}

const char* mesh_format_names() { return "obj|msh|vtk|vtu|ply"; }

const char* mesh_formats_help() {
  return "Mesh files: the format follows the extension (no extension: OBJ). .obj: v, vt, f v/vt;\n"
         ".msh: Gmsh MSH 4.1 ASCII, a named physical group per face, UVs as the node data view \"uv\" (u, v, 0);\n"
         ".vtk (legacy) and .vtu (XML), ASCII: UVs as point data \"uv\", the face as cell data \"face_id\";\n"
         ".ply (ASCII): u v as vertex properties, face_id as a face property. Formats other than OBJ hold one\n"
         "UV per point: a layout cut along seams gets a point per vertex use there. Another extension: exit 2.\n";
}

int write_mesh(const std::string& path, MeshFormat format, const MeshDescription& mesh, std::string& error) {
  const bool uv_per_point = format != MeshFormat::obj;
  const Prepared p(mesh, uv_per_point);
  std::string why;
  if (!p.consistent(uv_per_point, why)) {
    error = path + ": not written: inconsistent mesh (" + why + ")";
    return kExitIo;
  }
  TextOut out;
  if (!out.open(path)) {
    error = out.error();
    return out.failure_code();
  }
  const int digits = mesh.digits17 ? 17 : 0;
  Writer w(out, digits);
  switch (format) {
    case MeshFormat::obj: write_obj(out, digits, p); break;
    case MeshFormat::msh: write_msh(w, p); break;
    case MeshFormat::vtk: write_vtk(w, p); break;
    case MeshFormat::vtu: write_vtu(w, p); break;
    case MeshFormat::ply: write_ply(w, p); break;
  }
  if (!out.close()) {
    error = out.error();
    return out.failure_code();
  }
  return kExitOk;
}

int write_mesh(const std::string& path, const MeshDescription& mesh, std::string& error) {
  MeshFormat format = MeshFormat::obj;
  if (!mesh_format_of(path, format, error)) return kExitUsage;
  return write_mesh(path, format, mesh, error);
}

}  // namespace wefm_cli
