#pragma once
// Every mesh or layout file the tool writes: one neutral description of a surface mesh (points,
// optional UVs, triangles or quads, a face group per element) and one writer per file format,
// chosen by the file's extension. The bytes go through TextOut (text_out.hpp): a file is replaced
// whole or not at all.
//
//   .obj  v / vt / f (v/vt where there are UVs), `g NAME` per group where asked; a UV per corner is
//         kept as it is (a seam vertex has one `v` and one `vt` per use). The lines are those of
//         common/obj_lines, which the library's own OBJ files use too.
//   .msh  Gmsh MSH 4.1 ASCII: one surface entity and one named physical group per face group. MSH
//         nodes carry no UV (meshio reads no parametric nodes), so UVs go into a $NodeData view
//         "uv" of 3 components (u, v, 0): Gmsh views are scalars, vectors or tensors.
//   .vtk  VTK legacy ASCII unstructured grid: UVs as point data "uv" (2 components), the group tag
//         as cell data "face_id".
//   .vtu  VTK XML ASCII unstructured grid: the same arrays as .vtk.
//   .ply  PLY ASCII: u v as vertex properties, face_id as a face property, group names as comments.
// MSH, VTK, VTU and PLY hold one UV per point: a mesh with UVs per corner (a flattened face cut
// along seams) is written with one point per vertex use, the seam's points doubled.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace wefm_cli {

enum class MeshFormat { obj, msh, vtk, vtu, ply };

// The format of `path` by its extension (any case). A name without one (/dev/null, a FIFO, "out")
// is OBJ, the tool's format before there were others. Any other extension: false with a message
// listing the formats (the caller exits 2 before doing any work).
bool mesh_format_of(const std::string& path, MeshFormat& format, std::string& error);
// --format NAME ("obj", "msh", "vtk", "vtu", "ply"); false with a message otherwise.
bool parse_mesh_format(const std::string& name, MeshFormat& format, std::string& error);
// ".obj", ".msh", ...
const char* mesh_format_extension(MeshFormat format);
// One line for option help: "obj|msh|vtk|vtu|ply".
const char* mesh_format_names();
// A paragraph for a command's --help: what each format holds.
const char* mesh_formats_help();

// A read-only view of an array the caller keeps alive while the file is written.
template <class T>
struct ArrayView {
  const T* data = nullptr;
  size_t size = 0;
  ArrayView() = default;
  ArrayView(const std::vector<T>& v) : data(v.data()), size(v.size()) {}  // NOLINT: implicit by design
  bool empty() const { return size == 0; }
  const T& operator[](size_t i) const { return data[i]; }
};

struct MeshGroup {
  int tag = 1;
  std::string name;  // MSH physical name, OBJ `g`, PLY comment
};

struct MeshDescription {
  std::vector<std::string> comments;  // header lines (OBJ `#`, PLY `comment`, the VTK title, ...)
  ArrayView<double> xyz;              // 3 per point
  ArrayView<double> uv;               // 2 per UV; empty: no UVs
  ArrayView<int32_t> corner_uv;       // per element corner, an index into uv; empty: uv is per point
  ArrayView<int32_t> elements;        // nodes_per_element 0-based points per element
  int nodes_per_element = 3;          // 3 (triangles) or 4 (quads; a fourth node -1 is a triangle among them)
  ArrayView<int> element_group;       // per element, a group tag; empty: every element in groups[0]
  ArrayView<int> point_group;         // MSH entity each point is listed under; empty: its first element's
  std::vector<MeshGroup> groups;      // every tag used, in the order MSH lists its entities
  bool obj_groups = false;            // OBJ: a `g NAME` line where the group changes
  // Numbers as the shortest text that reads back to the same double, or as printf's %.17g (the
  // same value, longer text; kept where a command wrote it so before, for identical bytes).
  bool digits17 = false;
};

// Writes `mesh` to `path` in `format`. Returns kExitOk, kExitIo or the stop's exit code, with `error`.
int write_mesh(const std::string& path, MeshFormat format, const MeshDescription& mesh, std::string& error);
// The same, the format from the path's extension (already checked by the caller with mesh_format_of).
int write_mesh(const std::string& path, const MeshDescription& mesh, std::string& error);

}  // namespace wefm_cli
