#include "wefm/core/mesh/mesh_io.hpp"

#include <algorithm>
#include <cctype>

#include "mesh_io/readers.hpp"
#include "wefm/core/mesh/obj_writer.hpp"
#include "wefm/core/sys/error.hpp"

namespace wefm {

namespace {

std::string lower_ext(const std::string& path) {
  const auto dot = path.find_last_of('.');
  std::string e = dot == std::string::npos ? "" : path.substr(dot + 1);
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return e;
}

}  // namespace

ReadResult read_mesh(const std::string& path, double merge_tolerance) {
  const std::string ext = lower_ext(path);
  if (ext == "obj") return io::read_obj(path);
  if (ext == "stl") return io::read_stl(path, merge_tolerance);
  if (ext == "off") return io::read_off(path);
  if (ext == "ply") return io::read_ply(path);
  fail(Errc::unsupported, "unsupported mesh format '." + ext + "' for '" + path + "' (OBJ, OFF, STL, PLY)");
}

void write_obj_uv(const std::string& path, const TriMesh& m, const Topology& tp, const VectorXc& uv) {
  ObjWriter w(path);
  w.comment("wefm flattened face: v = 3D, vt = UV per vertex use");
  for (const Vec3& p : m.vertices) w.vertex(p[0], p[1], p[2]);
  for (Index u = 0; u < static_cast<Index>(uv.size()); ++u) w.texture(uv[u].real(), uv[u].imag());
  for (std::size_t t = 0; t < m.triangles.size(); ++t) w.face(m.triangles[t].data(), &tp.corner_use[3 * t], 3);
  w.commit();
}

}  // namespace wefm
