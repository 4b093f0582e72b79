#include <string>

#include "wefm/common/element_corners.hpp"
#include "wefm/core/mesh/obj_writer.hpp"
#include "wefm/core/meshing/domain_mesh.hpp"

namespace wefm::meshing {

void write_obj(const std::string& path, const DomainMesh& m) {
  ObjWriter w(path);
  const std::size_t npe = static_cast<std::size_t>(m.nodes_per_element);
  w.comment("wefm domain mesh: " + std::to_string(m.xyz.size()) + " nodes, " + std::to_string(m.elements.size() / npe) + " elements");
  for (const Vec3& p : m.xyz) w.vertex(p.x(), p.y(), p.z());
  for (const P2& p : m.uv) w.texture(p.x(), p.y());
  // A node's UV is its own: the same index for v and vt.
  // A quad-dominant mesh's triangle ends in -1.
  for (std::size_t e = 0; e + npe <= m.elements.size(); e += npe) {
    const std::size_t corners = wefm_common::element_corners(&m.elements[e], m.nodes_per_element);
    w.face(&m.elements[e], &m.elements[e], corners);
  }
  w.commit();
}

}  // namespace wefm::meshing
