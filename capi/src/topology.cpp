// Topology: caller edges, loops and seams; queries of what was given or derived.
#include "handles.hpp"

using wefm::capi::Access;
using wefm::capi::on_face;

extern "C" {

WEFM_API wefm_status wefm_face_clear_topology(wefm_face* face) {
  WEFM_REQUIRE(face, "wefm_face_clear_topology");
  return on_face(face, Access::change, "wefm_face_clear_topology", [&] { face->face.clear_topology(); });
}

WEFM_API wefm_status wefm_face_add_edge(wefm_face* face, int64_t n, const int32_t* chain, int32_t* edge_id) {
  WEFM_REQUIRE(face, "wefm_face_add_edge");
  WEFM_REQUIRE(chain, "wefm_face_add_edge");
  return on_face(face, Access::change, "wefm_face_add_edge", [&] {
    if (n < 1) throw wefm::Error(wefm::Errc::invalid_argument, "an edge needs at least one vertex (n = " + std::to_string(n) + ")");
    const wefm::Index id = face->face.add_edge(std::vector<wefm::Index>(chain, chain + n));
    if (edge_id) *edge_id = id;
  });
}

WEFM_API wefm_status wefm_face_add_loop(wefm_face* face, int64_t n, const int32_t* edges, const int32_t* reversed, int32_t* loop_id) {
  WEFM_REQUIRE(face, "wefm_face_add_loop");
  WEFM_REQUIRE(edges, "wefm_face_add_loop");
  return on_face(face, Access::change, "wefm_face_add_loop", [&] {
    if (n < 1) throw wefm::Error(wefm::Errc::invalid_argument, "a loop needs at least one edge use (n = " + std::to_string(n) + ")");
    std::vector<wefm::EdgeUse> loop(static_cast<size_t>(n));
    for (int64_t j = 0; j < n; ++j) loop[static_cast<size_t>(j)] = {edges[j], reversed ? reversed[j] != 0 : false};
    const wefm::Index id = face->face.add_loop(std::move(loop));
    if (loop_id) *loop_id = id;
  });
}

WEFM_API wefm_status wefm_face_set_outer_loop(wefm_face* face, int32_t loop) {
  WEFM_REQUIRE(face, "wefm_face_set_outer_loop");
  return on_face(face, Access::change, "wefm_face_set_outer_loop", [&] { face->face.set_outer_loop(loop); });
}

WEFM_API wefm_status wefm_face_add_seams(wefm_face* face, int64_t n, const int32_t* pairs) {
  WEFM_REQUIRE(face, "wefm_face_add_seams");
  WEFM_REQUIRE(pairs, "wefm_face_add_seams");
  return on_face(face, Access::change, "wefm_face_add_seams", [&] {
    if (n < 0) throw wefm::Error(wefm::Errc::invalid_argument, "negative seam count");
    std::vector<std::pair<wefm::Index, wefm::Index>> s(static_cast<size_t>(n));
    for (int64_t j = 0; j < n; ++j) s[static_cast<size_t>(j)] = {pairs[2 * j], pairs[2 * j + 1]};
    face->face.add_seams(s);
  });
}

WEFM_API wefm_status wefm_face_set_edge_mode(wefm_face* face, int32_t edge, int mode) {
  WEFM_REQUIRE(face, "wefm_face_set_edge_mode");
  return on_face(face, Access::change, "wefm_face_set_edge_mode", [&] { face->face.set_edge_mode(edge, static_cast<wefm::EdgeMode>(mode)); });
}

WEFM_API wefm_status wefm_face_build(wefm_face* face) {
  WEFM_REQUIRE(face, "wefm_face_build");
  return on_face(face, Access::change, "wefm_face_build", [&] { (void)face->face.topology(); });
}

WEFM_API wefm_status wefm_face_edge_count(wefm_face* face, int64_t* count) {
  WEFM_REQUIRE(face, "wefm_face_edge_count");
  WEFM_REQUIRE(count, "wefm_face_edge_count");
  return on_face(face, Access::read, "wefm_face_edge_count", [&] { *count = static_cast<int64_t>(face->face.topology().edges.size()); });
}

static const wefm::Topology& topo_with_edge(wefm_face* face, int32_t edge) {
  const wefm::Topology& tp = face->face.topology();
  if (edge < 0 || static_cast<size_t>(edge) >= tp.edges.size())
    throw wefm::Error(wefm::Errc::out_of_range, "edge " + std::to_string(edge) + " does not exist (" + std::to_string(tp.edges.size()) + " edges)");
  return tp;
}

static const wefm::Topology& topo_with_loop(wefm_face* face, int32_t loop) {
  const wefm::Topology& tp = face->face.topology();
  if (loop < 0 || static_cast<size_t>(loop) >= tp.loops.size())
    throw wefm::Error(wefm::Errc::out_of_range, "loop " + std::to_string(loop) + " does not exist (" + std::to_string(tp.loops.size()) + " loops)");
  return tp;
}

WEFM_API wefm_status wefm_face_get_edge(wefm_face* face, int32_t edge, int32_t* chain, int64_t capacity, int64_t* count) {
  WEFM_REQUIRE(face, "wefm_face_get_edge");
  WEFM_REQUIRE(count, "wefm_face_get_edge");
  return on_face(face, Access::read, "wefm_face_get_edge", [&] { wefm::capi::copy_out(topo_with_edge(face, edge).edges[static_cast<size_t>(edge)], chain, capacity, count); });
}

WEFM_API wefm_status wefm_face_edge_is_repeated(wefm_face* face, int32_t edge, int32_t* repeated) {
  WEFM_REQUIRE(face, "wefm_face_edge_is_repeated");
  WEFM_REQUIRE(repeated, "wefm_face_edge_is_repeated");
  return on_face(face, Access::read, "wefm_face_edge_is_repeated", [&] { *repeated = topo_with_edge(face, edge).edge_repeated[static_cast<size_t>(edge)] >= 0 ? 1 : 0; });
}

WEFM_API wefm_status wefm_face_loop_count(wefm_face* face, int64_t* count) {
  WEFM_REQUIRE(face, "wefm_face_loop_count");
  WEFM_REQUIRE(count, "wefm_face_loop_count");
  return on_face(face, Access::read, "wefm_face_loop_count", [&] { *count = static_cast<int64_t>(face->face.topology().loops.size()); });
}

WEFM_API wefm_status wefm_face_get_loop(wefm_face* face, int32_t loop, int32_t* edge_uses, int64_t capacity, int64_t* count) {
  WEFM_REQUIRE(face, "wefm_face_get_loop");
  WEFM_REQUIRE(count, "wefm_face_get_loop");
  return on_face(face, Access::read, "wefm_face_get_loop", [&] {
    std::vector<int32_t> v;
    for (const wefm::EdgeUse& u : topo_with_loop(face, loop).loops[static_cast<size_t>(loop)]) v.insert(v.end(), {u.edge, u.reversed ? 1 : 0});
    wefm::capi::copy_out(v, edge_uses, capacity, count);
  });
}

WEFM_API wefm_status wefm_face_get_loop_uses(wefm_face* face, int32_t loop, int32_t* uses, int64_t capacity, int64_t* count) {
  WEFM_REQUIRE(face, "wefm_face_get_loop_uses");
  WEFM_REQUIRE(count, "wefm_face_get_loop_uses");
  return on_face(face, Access::read, "wefm_face_get_loop_uses", [&] { wefm::capi::copy_out(topo_with_loop(face, loop).loop_uses[static_cast<size_t>(loop)], uses, capacity, count); });
}

WEFM_API wefm_status wefm_face_outer_loop(wefm_face* face, int32_t* loop) {
  WEFM_REQUIRE(face, "wefm_face_outer_loop");
  WEFM_REQUIRE(loop, "wefm_face_outer_loop");
  return on_face(face, Access::read, "wefm_face_outer_loop", [&] { *loop = face->face.topology().outer_loop; });
}

WEFM_API wefm_status wefm_face_use_count(wefm_face* face, int64_t* count) {
  WEFM_REQUIRE(face, "wefm_face_use_count");
  WEFM_REQUIRE(count, "wefm_face_use_count");
  return on_face(face, Access::read, "wefm_face_use_count", [&] { *count = face->face.topology().use_count; });
}

WEFM_API wefm_status wefm_face_get_use_vertices(wefm_face* face, int32_t* vertices, int64_t capacity, int64_t* count) {
  WEFM_REQUIRE(face, "wefm_face_get_use_vertices");
  WEFM_REQUIRE(count, "wefm_face_get_use_vertices");
  return on_face(face, Access::read, "wefm_face_get_use_vertices", [&] { wefm::capi::copy_out(face->face.topology().use_vertex, vertices, capacity, count); });
}

WEFM_API wefm_status wefm_face_get_triangle_uses(wefm_face* face, int32_t* uses, int64_t capacity, int64_t* count) {
  WEFM_REQUIRE(face, "wefm_face_get_triangle_uses");
  WEFM_REQUIRE(count, "wefm_face_get_triangle_uses");
  return on_face(face, Access::read, "wefm_face_get_triangle_uses", [&] { wefm::capi::copy_out(face->face.topology().corner_use, uses, capacity, count); });
}

WEFM_API wefm_status wefm_face_get_vertex_uses(wefm_face* face, int32_t vertex, int32_t* uses, int64_t capacity, int64_t* count) {
  WEFM_REQUIRE(face, "wefm_face_get_vertex_uses");
  WEFM_REQUIRE(count, "wefm_face_get_vertex_uses");
  return on_face(face, Access::read, "wefm_face_get_vertex_uses", [&] {
    const wefm::Topology& tp = face->face.topology();
    if (vertex < 0 || static_cast<size_t>(vertex) >= face->face.mesh().vertices.size())
      throw wefm::Error(wefm::Errc::out_of_range, "vertex " + std::to_string(vertex) + " is out of range [0, " + std::to_string(face->face.mesh().vertices.size()) + ")");
    std::vector<int32_t> v;
    for (wefm::Index u = 0; u < tp.use_count; ++u)
      if (tp.use_vertex[static_cast<size_t>(u)] == vertex) v.push_back(u);
    wefm::capi::copy_out(v, uses, capacity, count);
  });
}

}
