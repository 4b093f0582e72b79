// CAD import of faces BRepMesh hands over in a shape no flattener accepts: a face whose inner wire
// touches its outer wire at a vertex (facets in two fans there), an INTERNAL face (its edges read as
// constraint lines), and the ear-clipping fill used where BRepMesh's facets miss the boundary.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepTools.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Vertex.hxx>
#include <TopoDS_Wire.hxx>
#include <gp_Sphere.hxx>
#include <gp_Pln.hxx>
#include <BRepBuilderAPI_MakeVertex.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Poly_PolygonOnTriangulation.hxx>
#include <Poly_Triangulation.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS_Edge.hxx>

#include "cad_face_import.hpp"
#include "cad_model.hpp"
#include "cad_polygon_fill.hpp"
#include "cad_wefm.hpp"

namespace {

using wefm_cad::CadFace;

wefm_cad::CadModel load_brep(const TopoDS_Shape& shape, const char* name) {
  const std::string path = (std::filesystem::temp_directory_path() / name).string();
  REQUIRE(BRepTools::Write(shape, path.c_str()));
  wefm_cad::CadModel m;
  std::string error;
  const bool ok = wefm_cad::load_cad_model(path, wefm_cad::TessellationSettings{}, m, error);
  std::filesystem::remove(path);
  INFO(error);
  REQUIRE(ok);
  return m;
}

// Per vertex, the number of fans of its triangles (triangles joined across edges of two).
std::vector<int> fans_per_vertex(const CadFace& f) {
  const std::vector<int32_t>& t = f.triangles;
  std::map<std::pair<int32_t, int32_t>, std::vector<size_t>> edge_tris;
  for (size_t k = 0; k < t.size(); ++k) edge_tris[std::minmax(t[k], t[k - k % 3 + (k % 3 + 1) % 3])].push_back(k / 3);
  std::vector<int> fans(f.xyz.size() / 3, 0);
  for (size_t v = 0; v < fans.size(); ++v) {
    std::vector<size_t> tris;
    for (size_t k = 0; k < t.size(); ++k)
      if (t[k] == static_cast<int32_t>(v)) tris.push_back(k / 3);
    std::set<size_t> seen;
    for (size_t start : tris) {
      if (seen.count(start)) continue;
      ++fans[v];
      std::vector<size_t> stack = {start};
      seen.insert(start);
      while (!stack.empty()) {
        const size_t tri = stack.back();
        stack.pop_back();
        for (size_t c = 0; c < 3; ++c) {
          const int32_t w = t[3 * tri + c];
          if (w == static_cast<int32_t>(v)) continue;
          const auto& ts = edge_tris[std::minmax(static_cast<int32_t>(v), w)];
          if (ts.size() != 2) continue;
          for (size_t o : ts)
            if (seen.insert(o).second) stack.push_back(o);
        }
      }
    }
  }
  return fans;
}

// The face flattens and its domain meshes (the whole per-face path of mesh-model).
void check_flattens_and_meshes(const CadFace& f) {
  wefm_face* face = nullptr;
  REQUIRE(wefm_face_create(&face) == WEFM_OK);
  std::string error;
  CHECK_MESSAGE(wefm_cad::set_face_from_cad(face, f, error) == WEFM_OK, error);
  CHECK_MESSAGE(wefm_face_solve(face) == WEFM_OK, wefm_face_last_error(face));
  wefm_mesh_options o;
  wefm_mesh_options_init(&o, sizeof o);
  o.size = 1.0;  // a tenth of the test faces' width
  wefm_domain_mesh* mesh = nullptr;
  CHECK_MESSAGE(wefm_face_mesh_domain(face, &o, &mesh) == WEFM_OK, wefm_face_last_error(face));
  if (mesh) {
    wefm_mesh_report r;
    wefm_mesh_report_init(&r, sizeof r);
    REQUIRE(wefm_domain_mesh_get_report(mesh, &r) == WEFM_OK);
    CHECK(r.elements > 0);
    CHECK(r.lambda_min > 0);
  }
  wefm_domain_mesh_release(mesh);
  wefm_face_release(face);
}

// A 10 x 10 square with a triangular hole whose corner is the square's vertex at (5, 0).
TopoDS_Face pinched_square() {
  const TopoDS_Vertex pinch = BRepBuilderAPI_MakeVertex(gp_Pnt(5, 0, 0));
  BRepBuilderAPI_MakePolygon outer;
  outer.Add(gp_Pnt(0, 0, 0));
  outer.Add(pinch);
  for (const gp_Pnt& p : {gp_Pnt(10, 0, 0), gp_Pnt(10, 10, 0), gp_Pnt(0, 10, 0)}) outer.Add(p);
  outer.Close();
  BRepBuilderAPI_MakePolygon inner;
  inner.Add(pinch);
  inner.Add(gp_Pnt(3, 4, 0));
  inner.Add(gp_Pnt(7, 4, 0));
  inner.Close();
  BRepBuilderAPI_MakeFace mk(gp_Pln(gp::Origin(), gp::DZ()), outer.Wire());
  mk.Add(inner.Wire());  // clockwise: the face on its left
  REQUIRE(mk.IsDone());
  return mk.Face();
}

}  // namespace

TEST_CASE("a face whose hole touches its outer wire at a vertex: one vertex per fan, loops walked, meshed") {
  const wefm_cad::CadModel m = load_brep(pinched_square(), "wefm_pinched_square.brep");
  REQUIRE(m.faces.size() == 1);
  const CadFace& f = m.faces.front();
  INFO(f.error);
  REQUIRE(f.error.empty());
  for (int n : fans_per_vertex(f)) CHECK(n <= 1);
  // The pinch point is now two vertices at the same place, one per fan.
  int at_pinch = 0;
  for (size_t v = 0; v < f.xyz.size() / 3; ++v)
    at_pinch += std::hypot(f.xyz[3 * v] - 5, f.xyz[3 * v + 1], f.xyz[3 * v + 2]) < 1e-9;
  CHECK(at_pinch == 2);
  // Every edge is still used once, each chain joins the next use's chain, and the outer loop is one of them.
  std::map<int32_t, int> uses;
  for (const auto& loop : f.loops) {
    for (size_t i = 0; i < loop.size(); ++i) {
      ++uses[loop[i].edge];
      const auto& a = f.edges[static_cast<size_t>(loop[i].edge)].vertices;
      const auto& b = f.edges[static_cast<size_t>(loop[(i + 1) % loop.size()].edge)].vertices;
      const int32_t end = loop[i].reversed ? a.front() : a.back();
      const int32_t start = loop[(i + 1) % loop.size()].reversed ? b.back() : b.front();
      CHECK(end == start);
    }
  }
  CHECK(uses.size() == f.edges.size());
  for (const auto& [edge, n] : uses) CHECK(n == 1);
  CHECK(f.outer_loop >= 0);
  CHECK(f.outer_loop < static_cast<int>(f.loops.size()));
  check_flattens_and_meshes(f);
}

TEST_CASE("an INTERNAL face keeps its wire as its boundary") {
  const TopoDS_Shape face = pinched_square().Oriented(TopAbs_INTERNAL);
  const wefm_cad::CadModel m = load_brep(face, "wefm_internal_face.brep");
  REQUIRE(m.faces.size() == 1);
  const CadFace& f = m.faces.front();
  INFO(f.error);
  REQUIRE(f.error.empty());
  size_t used = 0;
  for (const auto& loop : f.loops) used += loop.size();
  CHECK(used == f.edges.size());
  check_flattens_and_meshes(f);
}

TEST_CASE("a facet node lying on another inside the face is merged and its zero-area facets dropped") {
  // BRepMesh's facets of a sphere patch (a plane's or a cylinder's have no inside node), then one
  // inside node v doubled: its copy w (appended, so the edges' polygons keep their node numbers)
  // takes v's place in one facet (v, a, b), and two zero-area facets (v, a, w) and (v, w, b) close
  // the slit between them, as BRepMesh left gmsh_SampleCrankshaft4A's face 41 at a fine deflection.
  TopoDS_Face face = BRepBuilderAPI_MakeFace(gp_Sphere(gp_Ax3(), 5), 0, 1, 0, 1);
  BRepMesh_IncrementalMesh(face, 0.01, false, 0.2);
  TopLoc_Location loc;
  const Handle(Poly_Triangulation) tri = BRep_Tool::Triangulation(face, loc);
  REQUIRE(!tri.IsNull());
  REQUIRE(tri->HasUVNodes());
  TopTools_IndexedMapOfShape edges;
  TopExp::MapShapes(face, TopAbs_EDGE, edges);
  const wefm_cad::CadFace before = wefm_cad::import_face(face, edges, 1);
  REQUIRE(before.error.empty());
  // An inside node: on no edge's polygon.
  std::set<int> on_edges;
  for (int k = 1; k <= edges.Extent(); ++k) {
    const Handle(Poly_PolygonOnTriangulation) poly = BRep_Tool::PolygonOnTriangulation(TopoDS::Edge(edges(k)), tri, loc);
    REQUIRE(!poly.IsNull());
    for (int i = 1; i <= poly->NbNodes(); ++i) on_edges.insert(poly->Node(i));
  }
  int split = 0, v = 0, a = 0, b = 0;
  for (int t = 1; t <= tri->NbTriangles() && !split; ++t) {
    int n[3];
    tri->Triangle(t).Get(n[0], n[1], n[2]);
    for (int c = 0; c < 3 && !split; ++c)
      if (!on_edges.count(n[c])) split = t, v = n[c], a = n[(c + 1) % 3], b = n[(c + 2) % 3];
  }
  REQUIRE(split > 0);
  const int nodes = tri->NbNodes(), w = nodes + 1;
  Handle(Poly_Triangulation) doubled = new Poly_Triangulation(nodes + 1, tri->NbTriangles() + 2, true);
  for (int i = 1; i <= nodes; ++i) doubled->SetNode(i, tri->Node(i)), doubled->SetUVNode(i, tri->UVNode(i));
  doubled->SetNode(w, tri->Node(v)), doubled->SetUVNode(w, tri->UVNode(v));
  for (int t = 1; t <= tri->NbTriangles(); ++t) doubled->SetTriangle(t, t == split ? Poly_Triangle(w, a, b) : tri->Triangle(t));
  doubled->SetTriangle(tri->NbTriangles() + 1, Poly_Triangle(v, a, w));
  doubled->SetTriangle(tri->NbTriangles() + 2, Poly_Triangle(v, w, b));
  BRep_Builder builder;
  for (int k = 1; k <= edges.Extent(); ++k) {
    const TopoDS_Edge e = TopoDS::Edge(edges(k));
    builder.UpdateEdge(e, BRep_Tool::PolygonOnTriangulation(e, tri, loc), doubled, loc);
  }
  builder.UpdateFace(face, doubled);
  const wefm_cad::CadFace after = wefm_cad::import_face(face, edges, 1);
  INFO(after.error);
  REQUIRE(after.error.empty());
  // The copy is one vertex with v again, and its two zero-area facets are gone: the face is as before.
  CHECK(after.xyz.size() == before.xyz.size());
  CHECK(after.triangles.size() == before.triangles.size());
  CHECK(after.dropped_triangles == before.dropped_triangles + 2);
  for (size_t t = 0; t + 2 < after.triangles.size(); t += 3) {
    const double* p[3];
    for (size_t c = 0; c < 3; ++c) p[c] = &after.xyz[3 * static_cast<size_t>(after.triangles[t + c])];
    const double u[3] = {p[1][0] - p[0][0], p[1][1] - p[0][1], p[1][2] - p[0][2]};
    const double w[3] = {p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]};
    const double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    CHECK(std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) > 1e-9);
  }
}

TEST_CASE("fill_polygon covers a polygon as a disk, also where it crosses itself") {
  struct Case {
    const char* name;
    std::vector<std::array<double, 2>> p;
  };
  // A comb (non-convex, ears only at some corners), clockwise; a thin crescent whose two chord
  // polygons cross (no ear at all part way); a polygon with a repeated point.
  std::vector<std::array<double, 2>> comb = {{0, 0}, {0, 3}, {1, 3}, {1, 1}, {2, 1}, {2, 3}, {3, 3}, {3, 0}};
  std::vector<std::array<double, 2>> crescent;
  for (int i = 0; i <= 8; ++i) crescent.push_back({std::cos(0.3 * i), std::sin(0.3 * i)});
  for (int i = 8; i >= 0; --i) crescent.push_back({0.999 * std::cos(0.3 * i + 0.15), 0.999 * std::sin(0.3 * i + 0.15)});
  const Case cases[] = {{"comb", comb}, {"crescent", crescent}, {"repeat", {{0, 0}, {2, 0}, {2, 0}, {2, 2}, {0, 2}}}};
  for (const Case& c : cases) {
    CAPTURE(c.name);
    const auto tris = wefm_cad::fill_polygon(c.p);
    const size_t n = c.p.size();
    REQUIRE(tris.size() == n - 2);
    // A disk: each polygon side in one triangle, each other triangle side in two, every corner used.
    std::map<std::pair<int, int>, int> sides;
    std::set<int> corners;
    for (const auto& t : tris)
      for (size_t k = 0; k < 3; ++k) {
        ++sides[std::minmax(t[k], t[(k + 1) % 3])];
        corners.insert(t[k]);
      }
    CHECK(corners.size() == n);
    for (const auto& [side, count] : sides) {
      const bool boundary = (side.second - side.first == 1) || (side.first == 0 && side.second == static_cast<int>(n) - 1);
      CHECK(count == (boundary ? 1 : 2));
    }
  }
  CHECK(wefm_cad::fill_polygon({{0, 0}, {1, 0}}).empty());
  // The comb's triangles all turn counter-clockwise and add up to its area.
  double area = 0;
  for (const auto& t : wefm_cad::fill_polygon(comb)) {
    const auto &a = comb[static_cast<size_t>(t[0])], &b = comb[static_cast<size_t>(t[1])], &c = comb[static_cast<size_t>(t[2])];
    const double twice = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    CHECK(twice > 0);
    area += 0.5 * twice;
  }
  CHECK(area == doctest::Approx(7.0));
}
