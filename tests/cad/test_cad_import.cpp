// CAD import through the public C API: a STEP cylinder's lateral face arrives as an annulus with its
// seam as one repeated edge, and flattens periodic to a rectangle with zero distortion; model edges
// keep their ids across faces; sphere poles and a cone apex become single vertices.
#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCone.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakePrism.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRepTools.hxx>
#include <gp_Circ.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Writer.hxx>

#include "cad_edge_nodes.hpp"
#include "cad_model.hpp"
#include "cad_wefm.hpp"

namespace {

using wefm_cad::CadFace;

constexpr double kPi = 3.14159265358979323846;

const CadFace* face_of_type(const wefm_cad::CadModel& m, const std::string& type) {
  for (const CadFace& f : m.faces)
    if (f.surface_type == type) return &f;
  return nullptr;
}

wefm_cad::CadModel load(const std::string& path) {
  wefm_cad::CadModel model;
  std::string error;
  const bool ok = wefm_cad::load_cad_model(path, wefm_cad::TessellationSettings{}, model, error);
  INFO(error);
  REQUIRE(ok);
  return model;
}

// Writes an OCCT shape to a temporary BREP file and imports it as a model.
wefm_cad::CadModel load_shape(const TopoDS_Shape& shape, const char* name) {
  const std::string path = (std::filesystem::temp_directory_path() / name).string();
  REQUIRE(BRepTools::Write(shape, path.c_str()));
  wefm_cad::CadModel m = load(path);
  std::filesystem::remove(path);
  return m;
}

struct Face {
  wefm_face* f = nullptr;
  Face() { REQUIRE(wefm_face_create(&f) == WEFM_OK); }
  ~Face() { wefm_face_release(f); }
};

template <class T, class G>
std::vector<T> fetch(G get) {
  int64_t n = 0;
  REQUIRE(get(nullptr, 0, &n) == WEFM_OK);
  std::vector<T> v(static_cast<size_t>(n));
  if (n) REQUIRE(get(v.data(), n, &n) == WEFM_OK);
  return v;
}

double cross(const std::array<double, 2>& o, const std::array<double, 2>& a, const std::array<double, 2>& b) {
  return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
}

// Area of the convex hull (monotone chain).
double hull_area(std::vector<std::array<double, 2>> p) {
  std::sort(p.begin(), p.end());
  std::vector<std::array<double, 2>> h(2 * p.size());
  size_t k = 0;
  for (size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  h.resize(k - 1);
  double a = 0;
  for (size_t i = 0; i < h.size(); ++i) {
    const auto& q = h[i];
    const auto& r = h[(i + 1) % h.size()];
    a += q[0] * r[1] - q[1] * r[0];
  }
  return 0.5 * std::fabs(a);
}

}  // namespace

TEST_CASE("STEP cylinder: the seam is one repeated edge and model edges keep their ids") {
  const wefm_cad::CadModel m = load(WEFM_TEST_DATA "/cylinder.step");
  CHECK(m.format == "step");
  REQUIRE(m.faces.size() == 3);
  const CadFace* cyl = face_of_type(m, "cylinder");
  REQUIRE(cyl);
  CHECK(cyl->error.empty());
  REQUIRE(cyl->loops.size() == 1);
  CHECK(cyl->loops[0].size() == 4);  // circle, seam, circle, seam reversed
  int seams = 0;
  for (const auto& e : cyl->edges) seams += e.seam;
  CHECK(seams == 1);
  // The seam is walked once each way.
  std::map<int32_t, std::vector<bool>> uses;
  for (const auto& u : cyl->loops[0]) uses[u.edge].push_back(u.reversed);
  for (const auto& [edge, dirs] : uses)
    if (cyl->edges[static_cast<size_t>(edge)].seam) CHECK((dirs.size() == 2 && dirs[0] != dirs[1]));
  // The circles are shared with the two planes under the same ids and with the same 3D points.
  for (const auto& e : cyl->edges) {
    if (e.seam) continue;
    int found = 0;
    for (const CadFace& f : m.faces) {
      if (&f == cyl) continue;
      for (const auto& g : f.edges) {
        if (g.id != e.id) continue;
        ++found;
        REQUIRE(g.vertices.size() == e.vertices.size());
        for (size_t i = 0; i < e.vertices.size(); ++i)
          for (int c = 0; c < 3; ++c)
            CHECK(f.xyz[3 * static_cast<size_t>(g.vertices[i]) + static_cast<size_t>(c)] ==
                  doctest::Approx(cyl->xyz[3 * static_cast<size_t>(e.vertices[i]) + static_cast<size_t>(c)]));
      }
    }
    CHECK(found == 1);
  }
}

TEST_CASE("STEP cylinder: the lateral face flattens periodic to a rectangle with zero distortion") {
  const wefm_cad::CadModel m = load(WEFM_TEST_DATA "/cylinder.step");
  const CadFace* cyl = face_of_type(m, "cylinder");
  REQUIRE(cyl);
  Face face;
  std::string error;
  REQUIRE_MESSAGE(wefm_cad::set_face_from_cad(face.f, *cyl, error) == WEFM_OK, error);
  REQUIRE(wefm_face_build(face.f) == WEFM_OK);
  int64_t edges = 0;
  REQUIRE(wefm_face_edge_count(face.f, &edges) == WEFM_OK);
  CHECK(edges == static_cast<int64_t>(cyl->edges.size()));
  int32_t seam_edge = -1;
  for (int32_t e = 0; e < edges; ++e) {
    int32_t repeated = 0;
    REQUIRE(wefm_face_edge_is_repeated(face.f, e, &repeated) == WEFM_OK);
    CHECK(repeated == (cyl->edges[static_cast<size_t>(e)].seam ? 1 : 0));
    if (repeated) seam_edge = e;
  }
  REQUIRE(seam_edge >= 0);
  // An annulus: the seam vertices have two uses each, all others one.
  int64_t uses = 0;
  REQUIRE(wefm_face_use_count(face.f, &uses) == WEFM_OK);
  CHECK(uses == static_cast<int64_t>(cyl->xyz.size() / 3 + cyl->edges[static_cast<size_t>(seam_edge)].vertices.size()));

  REQUIRE(wefm_face_set_edge_mode(face.f, seam_edge, WEFM_EDGE_PERIODIC) == WEFM_OK);
  REQUIRE(wefm_face_solve(face.f) == WEFM_OK);
  wefm_report r;
  wefm_report_init(&r);
  REQUIRE(wefm_face_get_report(face.f, &r) == WEFM_OK);
  CHECK(r.flipped_triangles == 0);
  CHECK(r.boundary_intersections == 0);
  CHECK(r.area_distortion_max < 1e-6);
  CHECK(r.angle_distortion_max < 1 + 1e-6);

  // Isometric up to one scale: every facet edge keeps its length ratio.
  const auto uv = fetch<double>([&](double* b, int64_t c, int64_t* n) { return wefm_face_get_uv(face.f, b, c, n); });
  const auto tri_uses =
      fetch<int32_t>([&](int32_t* b, int64_t c, int64_t* n) { return wefm_face_get_triangle_uses(face.f, b, c, n); });
  double lo = 1e300, hi = 0;
  for (size_t t = 0; t < tri_uses.size() / 3; ++t)
    for (int c = 0; c < 3; ++c) {
      const size_t a = 3 * t + static_cast<size_t>(c), b = 3 * t + static_cast<size_t>((c + 1) % 3);
      const int32_t va = cyl->triangles[a], vb = cyl->triangles[b];
      double d3 = 0;
      for (int k = 0; k < 3; ++k) {
        const double d = cyl->xyz[3 * static_cast<size_t>(va) + static_cast<size_t>(k)] -
                         cyl->xyz[3 * static_cast<size_t>(vb) + static_cast<size_t>(k)];
        d3 += d * d;
      }
      const double du = uv[2 * static_cast<size_t>(tri_uses[a])] - uv[2 * static_cast<size_t>(tri_uses[b])];
      const double dv = uv[2 * static_cast<size_t>(tri_uses[a]) + 1] - uv[2 * static_cast<size_t>(tri_uses[b]) + 1];
      const double ratio = std::sqrt((du * du + dv * dv) / d3);
      lo = std::min(lo, ratio);
      hi = std::max(hi, ratio);
    }
  CHECK(hi / lo < 1 + 1e-6);
  // A rectangle: convex, so its hull has the domain's area.
  std::vector<std::array<double, 2>> pts;
  for (size_t i = 0; i < uv.size() / 2; ++i) pts.push_back({uv[2 * i], uv[2 * i + 1]});
  CHECK(hull_area(pts) == doctest::Approx(r.uv_area).epsilon(1e-6));
}

TEST_CASE("sphere poles and a cone apex become single vertices and the topology is accepted") {
  struct Case {
    const char* name;
    TopoDS_Shape shape;
    const char* type;
    size_t degenerate;
  };
  const Case cases[] = {{"wefm_sphere.brep", BRepPrimAPI_MakeSphere(5.0).Shape(), "sphere", 2},
                        {"wefm_cone.brep", BRepPrimAPI_MakeCone(4.0, 0.0, 8.0).Shape(), "cone", 1}};
  for (const Case& c : cases) {
    CAPTURE(c.name);
    const wefm_cad::CadModel m = load_shape(c.shape, c.name);
    const CadFace* f = face_of_type(m, c.type);
    REQUIRE(f);
    CHECK(f->error.empty());
    size_t degenerate = 0, seams = 0;
    for (const auto& e : f->edges) {
      if (e.degenerated) {
        ++degenerate;
        CHECK(e.vertices.size() == 1);
      }
      seams += e.seam;
    }
    CHECK(degenerate == c.degenerate);
    CHECK(seams == 1);
    Face face;
    std::string error;
    REQUIRE_MESSAGE(wefm_cad::set_face_from_cad(face.f, *f, error) == WEFM_OK, error);
    CHECK_MESSAGE(wefm_face_build(face.f) == WEFM_OK, wefm_face_last_error(face.f));
  }
}

TEST_CASE("IGES and BREP cylinders import like the STEP one") {
  const TopoDS_Shape cylinder = BRepPrimAPI_MakeCylinder(10.0, 25.0).Shape();
  const auto tmp = std::filesystem::temp_directory_path();
  const std::string iges = (tmp / "wefm_cylinder.igs").string(), brep = (tmp / "wefm_cylinder.brep").string();
  IGESControl_Controller::Init();
  IGESControl_Writer writer("MM", 1);  // BRep mode: faces stay faces
  writer.AddShape(cylinder);
  writer.ComputeModel();
  REQUIRE(writer.Write(iges.c_str()));
  REQUIRE(BRepTools::Write(cylinder, brep.c_str()));
  for (const std::string& path : {iges, brep}) {
    CAPTURE(path);
    const wefm_cad::CadModel m = load(path);
    std::filesystem::remove(path);
    CHECK(m.faces.size() == 3);
    const CadFace* cyl = face_of_type(m, "cylinder");
    REQUIRE(cyl);
    CHECK(cyl->error.empty());
    int seams = 0;
    for (const auto& e : cyl->edges) seams += e.seam;
    CHECK(seams == 1);
    Face face;
    std::string error;
    REQUIRE_MESSAGE(wefm_cad::set_face_from_cad(face.f, *cyl, error) == WEFM_OK, error);
    CHECK_MESSAGE(wefm_face_build(face.f) == WEFM_OK, wefm_face_last_error(face.f));
  }
}

TEST_CASE("model edges are discretised once: nodes on the chain, closed edges at least a triangle, local sizes") {
  const wefm_cad::CadModel m = load(WEFM_TEST_DATA "/cylinder.step");
  // Local size = 2.5 x width (2 area / perimeter), and on a curved face that wraps round, at most
  // its radius of curvature: the disks (r = 10) are 10 wide, so 25; the lateral face (2 pi 10 x 25,
  // perimeter 2 (2 pi 10) + 2 x 25) is 17.9 wide but a tube of radius 10; all clamped to [h/8, h].
  const std::vector<double> sizes = wefm_cad::local_face_sizes(m, 30.0);
  REQUIRE(sizes.size() == 3);
  for (size_t k = 0; k < 3; ++k) {
    CAPTURE(m.faces[k].surface_type);
    // Faceted: a little below the smooth values (the radius from facets is r cos of half the
    // angle between neighbouring facets).
    if (m.faces[k].surface_type == "cylinder") CHECK(sizes[k] == doctest::Approx(10.0).epsilon(0.05));
    else CHECK(sizes[k] == doctest::Approx(25.0).epsilon(0.02));
  }
  CHECK(wefm_cad::local_face_sizes(m, 2.0) == std::vector<double>(3, 2.0));
  const auto nodes = wefm_cad::discretise_model_edges(m, 2.0);
  const CadFace* cyl = face_of_type(m, "cylinder");
  REQUIRE(cyl);
  for (const auto& e : cyl->edges) {
    REQUIRE(nodes.count(e.id));
    const auto& xyz = nodes.at(e.id).xyz;
    const size_t n = xyz.size() / 3;
    const double* first = &cyl->xyz[3 * static_cast<size_t>(e.vertices.front())];
    const double* last = &cyl->xyz[3 * static_cast<size_t>(e.vertices.back())];
    for (int c = 0; c < 3; ++c) {
      CHECK(xyz[static_cast<size_t>(c)] == first[c]);
      CHECK(xyz[3 * (n - 1) + static_cast<size_t>(c)] == last[c]);
    }
    if (e.seam) CHECK(n == 14);  // 25 / 2 = 12.5 rounds to 13 segments
    else CHECK(n >= 32);         // a circle of length ~62.8 at h = 2: ~31 segments
  }
  // A coarse size still leaves a closed edge three segments.
  for (const auto& [id, en] : wefm_cad::discretise_model_edges(m, 1000.0)) {
    bool closed = false;
    for (const auto& e : cyl->edges)
      if (e.id == id) closed = e.vertices.front() == e.vertices.back();
    if (closed) CHECK(en.xyz.size() / 3 == 4);
  }
}

TEST_CASE("graded edge discretisation: long edges shrink towards a vertex where a short edge ends") {
  // A 100 x 100 x 2 plate at h = 40: the rims are narrow (width 2, local size floored at h/8 = 5),
  // the edges of thickness 2 one segment each, so the long edges meet 2-long segments at every corner.
  const wefm_cad::CadModel m = load_shape(BRepPrimAPI_MakeBox(100.0, 100.0, 2.0).Shape(), "wefm_plate.brep");
  const double h = 40;
  const std::vector<double> sizes = wefm_cad::local_face_sizes(m, h);
  const auto uniform = wefm_cad::discretise_model_edges(m, h, sizes, 0.0);
  const auto graded = wefm_cad::discretise_model_edges(m, h, sizes, 0.3);
  REQUIRE(uniform.size() == 12);
  REQUIRE(graded.size() == 12);
  auto segments = [](const wefm_cad::EdgeNodes& e) {
    std::vector<double> l;
    for (size_t k = 0; k + 5 < e.xyz.size(); k += 3)
      l.push_back(std::sqrt(std::pow(e.xyz[k + 3] - e.xyz[k], 2) + std::pow(e.xyz[k + 4] - e.xyz[k + 1], 2) + std::pow(e.xyz[k + 5] - e.xyz[k + 2], 2)));
    return l;
  };
  int long_edges = 0;
  for (const auto& [id, e] : graded) {
    const std::vector<double> l = segments(e), u = segments(uniform.at(id));
    double total = 0;
    for (double x : l) total += x;
    CAPTURE(id);
    CAPTURE(total);
    // The ends stay the chain's ends, bit for bit (faces sharing the edge weld on them).
    for (int c = 0; c < 3; ++c) {
      CHECK(e.xyz[static_cast<size_t>(c)] == uniform.at(id).xyz[static_cast<size_t>(c)]);
      CHECK(e.xyz[e.xyz.size() - 3 + static_cast<size_t>(c)] == uniform.at(id).xyz[uniform.at(id).xyz.size() - 3 + static_cast<size_t>(c)]);
    }
    if (total < 50) {
      CHECK(l.size() == u.size());  // the thickness edges set the corner size; nothing to grade
      continue;
    }
    ++long_edges;
    // Uniform: 20 segments of 5. Graded: about the corner size (2) at both ends, growing by at
    // most about 1 + g per segment, never above the edge size.
    const double rim = h / 8;
    for (double x : u) CHECK(x == doctest::Approx(rim).epsilon(1e-6));
    CHECK(l.size() > u.size());
    CHECK(l.front() < 3.0);
    CHECK(l.back() < 3.0);
    CHECK(l.front() == doctest::Approx(l.back()).epsilon(1e-6));
    for (size_t k = 0; k < l.size(); ++k) {
      CHECK(l[k] <= rim * 1.05);
      if (k > 0) CHECK(std::max(l[k], l[k - 1]) / std::min(l[k], l[k - 1]) <= 1.45);
    }
  }
  CHECK(long_edges == 8);
}

TEST_CASE("graded edge discretisation: an edge shorter than the sampling step rises between two short ends") {
  // The 100 x 100 x 2 plate at h = 400: the long edges are a quarter of h, shorter than the step at
  // which sizes are sampled, and both their ends meet the 2-long thickness edges. The rims they bound
  // are needles sized by their width (2.5 x 2 = 5; their floor, h / 300, is below it). The edges grow
  // from 2 at each end by g per unit length to the rims' 5 instead of keeping 2 all along (50
  // segments, and the faces graded from them thousands of triangles).
  const wefm_cad::CadModel m = load_shape(BRepPrimAPI_MakeBox(100.0, 100.0, 2.0).Shape(), "wefm_plate_coarse.brep");
  const double h = 400;
  const auto graded = wefm_cad::discretise_model_edges(m, h, wefm_cad::local_face_sizes(m, h), 0.3);
  int long_edges = 0;
  for (const auto& [id, e] : graded) {
    std::vector<double> l;
    for (size_t k = 0; k + 5 < e.xyz.size(); k += 3)
      l.push_back(std::sqrt(std::pow(e.xyz[k + 3] - e.xyz[k], 2) + std::pow(e.xyz[k + 4] - e.xyz[k + 1], 2) + std::pow(e.xyz[k + 5] - e.xyz[k + 2], 2)));
    double total = 0;
    for (double x : l) total += x;
    if (total < 50) continue;
    ++long_edges;
    CAPTURE(id);
    CHECK(l.front() < 3.0);
    CHECK(l.back() < 3.0);
    CHECK(l.size() < 40);
    CHECK(*std::max_element(l.begin(), l.end()) > 2 * l.front());
    CHECK(*std::max_element(l.begin(), l.end()) <= 5 * 1.05);
    for (size_t k = 1; k < l.size(); ++k) CHECK(std::max(l[k], l[k - 1]) / std::min(l[k], l[k - 1]) <= 1.45);
  }
  CHECK(long_edges == 8);
}

TEST_CASE("edge segments shrink where a face is narrow, not across a gap outside it") {
  // A plate 10 thick whose outline has an arm 2 wide (0 < y < 2, 10 < x < 100) beside a slot 2
  // wide (2 < y < 4) open at x = 100. At h = 10 the arm's outer edge (y = 0 on top) faces the
  // arm's inner edge across 2 of material: segments about 2.5 x 2. The slot's far side (y = 4)
  // faces the arm across 2 of void: the face is not narrow there, its segments grow back to h.
  BRepBuilderAPI_MakePolygon outline;
  for (auto [x, y] : {std::pair<double, double>{0, 0}, {100, 0}, {100, 2}, {10, 2}, {10, 4}, {100, 4}, {100, 100}, {0, 100}})
    outline.Add(gp_Pnt(x, y, 0));
  outline.Close();
  const TopoDS_Shape plate = BRepPrimAPI_MakePrism(BRepBuilderAPI_MakeFace(outline.Wire()).Face(), gp_Vec(0, 0, 10)).Shape();
  const wefm_cad::CadModel m = load_shape(plate, "wefm_arm_plate.brep");
  const double h = 10;
  const auto nodes = wefm_cad::discretise_model_edges(m, h, wefm_cad::local_face_sizes(m, h), 0.3);
  // The segments of the edge from (x0, y, z) to (x1, y, z) in either direction.
  auto segments_of = [&](double x0, double x1, double y, double z) {
    std::vector<double> l;
    for (const auto& [id, e] : nodes) {
      const size_t n = e.xyz.size() / 3;
      const double* a = &e.xyz[0];
      const double* b = &e.xyz[3 * (n - 1)];
      auto at = [](const double* p, double x, double yy, double zz) { return std::fabs(p[0] - x) + std::fabs(p[1] - yy) + std::fabs(p[2] - zz) < 1e-6; };
      if (!((at(a, x0, y, z) && at(b, x1, y, z)) || (at(a, x1, y, z) && at(b, x0, y, z)))) continue;
      for (size_t k = 0; k + 1 < n; ++k)
        l.push_back(std::hypot(e.xyz[3 * k + 3] - e.xyz[3 * k], e.xyz[3 * k + 4] - e.xyz[3 * k + 1], e.xyz[3 * k + 5] - e.xyz[3 * k + 2]));
    }
    return l;
  };
  const std::vector<double> outer = segments_of(0, 100, 0, 10), far_side = segments_of(10, 100, 4, 10);
  REQUIRE(outer.size() > 2);
  REQUIRE(far_side.size() > 2);
  // Along the arm (x from 30 to 90: the middle of the edge's segments) about 5; never above h.
  for (double x : outer) CHECK(x <= h * 1.05);
  CHECK(outer[outer.size() / 2] == doctest::Approx(5.0).epsilon(0.15));
  CHECK(*std::max_element(far_side.begin(), far_side.end()) > 0.85 * h);
}

TEST_CASE("edge segments shrink along a tongue between two parallel edges, where no sample falls") {
  // A plate 10 thick whose outline has a tongue 0.2 wide and 6 long (0 < x < 6, 0 < y < 0.2) on the
  // left of its 24 x 30 body: the bottom edge (y = 0, 30 long, one chain segment) faces the tongue's
  // top (y = 0.2, 6 long, parallel) across 0.2. At h = 30 the bottom's size samples lie h / 4 apart;
  // none but the tip's vertex is on the tongue, and at the tip the top is reached round the end
  // edge, not across. Where the top's end at the root faces the bottom (x = 6) is a sample too, of
  // size 2.5 x 0.2, and the segments grade from it and from the tip: the longest over the tongue
  // 1.10 (9 segments) against 1.34 (7) without that sample.
  BRepBuilderAPI_MakePolygon outline;
  for (auto [x, y] : {std::pair<double, double>{0, 0}, {30, 0}, {30, 30}, {6, 30}, {6, 0.2}, {0, 0.2}}) outline.Add(gp_Pnt(x, y, 0));
  outline.Close();
  const TopoDS_Shape plate = BRepPrimAPI_MakePrism(BRepBuilderAPI_MakeFace(outline.Wire()).Face(), gp_Vec(0, 0, 10)).Shape();
  const wefm_cad::CadModel m = load_shape(plate, "wefm_tongue_plate.brep");
  const double h = 30;
  const auto nodes = wefm_cad::discretise_model_edges(m, h, std::vector<double>(m.faces.size(), h), 0.3);
  // The bottom edge on the plate's top face (z = 10): its segments over the tongue (x < 6).
  std::vector<double> over_tongue;
  for (const auto& [id, e] : nodes) {
    const size_t n = e.xyz.size() / 3;
    auto on_bottom = [&](size_t k) { return std::fabs(e.xyz[3 * k + 1]) < 1e-9 && std::fabs(e.xyz[3 * k + 2] - 10) < 1e-9; };
    if (n < 2 || !on_bottom(0) || !on_bottom(n - 1)) continue;
    for (size_t k = 0; k + 1 < n; ++k)
      if (std::max(e.xyz[3 * k], e.xyz[3 * k + 3]) <= 6 + 1e-9) over_tongue.push_back(std::fabs(e.xyz[3 * k + 3] - e.xyz[3 * k]));
  }
  REQUIRE(over_tongue.size() > 3);
  const double longest = *std::max_element(over_tongue.begin(), over_tongue.end());
  CAPTURE(longest);
  CAPTURE(over_tongue.size());
  CHECK(longest < 1.2);
}

// A strip 100 long and 2 wide (z = -1 to 1 between its long sides A: y = 0 and B: y = `across`), its
// chain vertices at `xs`, side A at height za(x) and side B at zb(x), 4 rows of facets between.
CadFace strip(const std::vector<double>& xs, const std::function<double(double)>& za, const std::function<double(double)>& zb,
              double across = 0.05) {
  constexpr int kRows = 4;
  CadFace f;
  f.index = 1;
  f.surface_type = "bspline";
  const auto columns = static_cast<int32_t>(xs.size());
  auto id = [&](int32_t i, int32_t r) { return i * (kRows + 1) + r; };
  for (double x : xs)
    for (int r = 0; r <= kRows; ++r) {
      const double v = static_cast<double>(r) / kRows;
      f.xyz.insert(f.xyz.end(), {x, across * v, za(x) + v * (zb(x) - za(x))});
    }
  for (int32_t i = 0; i + 1 < columns; ++i)
    for (int32_t r = 0; r < kRows; ++r)
      f.triangles.insert(f.triangles.end(), {id(i, r), id(i + 1, r), id(i + 1, r + 1), id(i, r), id(i + 1, r + 1), id(i, r + 1)});
  wefm_cad::CadEdge a, end, b, start;
  a.id = 1, end.id = 2, b.id = 3, start.id = 4;
  for (int32_t i = 0; i < columns; ++i) a.vertices.push_back(id(i, 0));
  for (int32_t r = 0; r <= kRows; ++r) end.vertices.push_back(id(columns - 1, r));
  for (int32_t i = columns; i-- > 0;) b.vertices.push_back(id(i, kRows));
  for (int32_t r = kRows + 1; r-- > 0;) start.vertices.push_back(id(0, r));
  for (wefm_cad::CadEdge* e : {&a, &end, &b, &start}) e->curve_type = "BSplineCurve";
  f.edges = {a, end, b, start};
  f.loops = {{{0, false}, {1, false}, {2, false}, {3, false}}};
  f.outer_loop = 0;
  return f;
}

// A model of the one strip face.
wefm_cad::CadModel strip_model(CadFace f, const char* path) {
  wefm_cad::CadModel m;
  m.path = path;
  m.format = "brep";
  m.bbox_diagonal = std::sqrt(100.0 * 100.0 + 2.0 * 2.0 + 0.05 * 0.05);
  m.linear_deflection = 1e-3 * m.bbox_diagonal;
  m.faces.push_back(std::move(f));
  m.edge_count = 4;
  return m;
}

double ramp(double x, double x0, double x1) { return std::clamp((x - x0) / (x1 - x0), 0.0, 1.0); }

// The strip twisted: its sides swap heights in the middle, A rising from z = -1 to 1 on one chain
// segment (x from 44 to 57), B falling from 1 to -1 on another (x from 42 to 57). There the sides
// pass 0.05 apart, at a place inside both chain segments (two skew segments), where no chain vertex
// or size sample lies: the nearest samples see the strip about three times as wide.
CadFace pinched_strip(double across = 0.05) {
  return strip({0, 10, 20, 30, 40, 42, 44, 57, 60, 70, 80, 90, 100}, [](double x) { return -1 + 2 * ramp(x, 44, 57); },
               [](double x) { return 1 - 2 * ramp(x, 42, 57); }, across);
}

TEST_CASE("edge segments shrink at a pinch of a face, down to its width, also between chain vertices") {
  const wefm_cad::CadModel m = strip_model(pinched_strip(), "hand-made twisted strip");
  const double h = 10;
  const std::vector<double> sizes(1, h);
  // The shortest segment of each long side.
  auto shortest = [](const std::map<long long, wefm_cad::EdgeNodes>& nodes, long long edge) {
    const std::vector<double>& p = nodes.at(edge).xyz;
    double s = 1e300;
    for (size_t k = 0; k + 5 < p.size(); k += 3) s = std::min(s, std::hypot(p[k + 3] - p[k], p[k + 4] - p[k + 1], p[k + 5] - p[k + 2]));
    return s;
  };
  const auto nodes = wefm_cad::discretise_model_edges(m, h, sizes, 0.3);
  for (long long side : {1LL, 3LL}) {
    CAPTURE(side);
    // About 2.5 times the 0.05 across: below h / 32 (0.31, the floor away from pinches) and below
    // 2.5 times the width the nearest samples see (0.14).
    CHECK(shortest(nodes, side) < 0.2);
    CHECK(shortest(nodes, side) > 0.05);
    // A few dozen segments more than the 10 at h, not hundreds.
    CHECK(nodes.at(side).xyz.size() / 3 < 100);
  }
  // A cusp (a corner under 10 degrees) within h / 2 of the pinch: the edges do not shrink there by
  // the width (shorter chords would only narrow the cusp's triangles), only grade down towards the
  // strip's 2-wide parts beyond (5 there) by 0.3 per unit length.
  const std::vector<wefm_cad::Cusp> cusps = {{{50.5, 0.0, 0.0}, 5.0}};
  const auto beside_cusp = wefm_cad::discretise_model_edges(m, h, sizes, 0.3, cusps);
  for (long long side : {1LL, 3LL}) {
    CAPTURE(side);
    CHECK(shortest(beside_cusp, side) > 1.5);
  }
}

TEST_CASE("at a pinch where the sides pass 0.01 apart, edge segments shrink below h / 300") {
  // pinched_strip with its sides 0.01 apart in y. Where two edges touch tangentially the width goes
  // to 0: at h / 300 (0.033 here) gmsh_Solid_56's face 31 kept Lo lambda 0.276 there.
  const wefm_cad::CadModel m = strip_model(pinched_strip(0.01), "hand-made twisted strip, 0.01 across");
  const double h = 10;
  const auto nodes = wefm_cad::discretise_model_edges(m, h, std::vector<double>(1, h), 0.3);
  for (long long side : {1LL, 3LL}) {
    CAPTURE(side);
    const std::vector<double>& p = nodes.at(side).xyz;
    double s = 1e300;
    for (size_t k = 0; k + 5 < p.size(); k += 3) s = std::min(s, std::hypot(p[k + 3] - p[k], p[k + 4] - p[k + 1], p[k + 5] - p[k + 2]));
    // About 2.5 times the 0.01 across, above the floor of h / 1000.
    CHECK(s < 0.03);
    CHECK(s >= 0.01 - 1e-12);
    CHECK(p.size() / 3 < 300);
  }
}

// The strip of pinched_strip twisted back a second time: the sides pass 0.05 apart again inside the
// chain segments from x = 74 (A) and 72 (B) to 87.
CadFace twice_pinched_strip() {
  return strip({0, 10, 20, 30, 40, 42, 44, 57, 60, 70, 72, 74, 87, 90, 100},
               [](double x) { return -1 + 2 * ramp(x, 44, 57) - 2 * ramp(x, 74, 87); },
               [](double x) { return 1 - 2 * ramp(x, 42, 57) + 2 * ramp(x, 72, 87); });
}

TEST_CASE("edge segments shrink at every pinch along an edge, not only the first") {
  const wefm_cad::CadModel m = strip_model(twice_pinched_strip(), "hand-made strip twisted twice");
  const double h = 10;
  const auto nodes = wefm_cad::discretise_model_edges(m, h, std::vector<double>(1, h), 0.3);
  // The shortest segment of a long side with its midpoint between x0 and x1.
  auto shortest = [&](long long edge, double x0, double x1) {
    const std::vector<double>& p = nodes.at(edge).xyz;
    double s = 1e300;
    for (size_t k = 0; k + 5 < p.size(); k += 3) {
      const double x = 0.5 * (p[k] + p[k + 3]);
      if (x > x0 && x < x1) s = std::min(s, std::hypot(p[k + 3] - p[k], p[k + 4] - p[k + 1], p[k + 5] - p[k + 2]));
    }
    return s;
  };
  for (long long side : {1LL, 3LL}) {
    CAPTURE(side);
    // Both pinches. A pinch sample was once kept only while below the last one added to the edge's
    // samples: one side lost its second pinch, its segments there 5.0 long across 0.05.
    CHECK(shortest(side, 40, 60) < 0.2);
    CHECK(shortest(side, 70, 90) < 0.2);
  }
}

// The strip narrowed to `across` (its sides at one height, y = 0 and `across`) from x = a to b, with
// ramps 2 long: a narrow arm of the face rather than a point where it pinches. Chain vertices every
// 10 and at the ramps' ends.
CadFace narrow_arm_strip(double a, double b, double across) {
  std::vector<double> xs = {a - 2, a, b, b + 2};
  for (int x = 0; x <= 100; x += 10) xs.push_back(x);
  std::sort(xs.begin(), xs.end());
  xs.erase(std::unique(xs.begin(), xs.end()), xs.end());
  return strip(xs, [=](double x) { return -1 + ramp(x, a - 2, a) - ramp(x, b, b + 2); },
               [=](double x) { return 1 - ramp(x, a - 2, a) + ramp(x, b, b + 2); }, across);
}

// The longest segment of an edge's nodes `p` lying between x0 and x1.
double longest_between(const std::vector<double>& p, double x0, double x1) {
  double longest = 0;
  for (size_t k = 0; k + 5 < p.size(); k += 3)
    if (std::min(p[k], p[k + 3]) > x0 && std::max(p[k], p[k + 3]) < x1)
      longest = std::max(longest, std::hypot(p[k + 3] - p[k], p[k + 4] - p[k + 1], p[k + 5] - p[k + 2]));
  return longest;
}

TEST_CASE("along a narrow arm of a face edge segments follow its width up to 200 segments, and take 200 on a longer arm") {
  struct Arm {
    double a, b, h, x0, x1, shortest, longest;
  };
  // An arm 0.05 across and 15 long: about 2.5 times the width (some 120 segments), where the floor
  // away from pinches (h / 32 = 0.31, once the floor on any run over 50 segments) left Lo lambda
  // under 0.1. One 60 long (480 segments at 2.5 times the width): about 60 / 200, not h / 32 (0.625,
  // the floor on such an arm before).
  for (const Arm& arm : {Arm{40, 55, 10, 41, 54, 0.05, 0.2}, Arm{20, 80, 20, 25, 75, 0.2, 0.4}}) {
    CAPTURE(arm.b - arm.a);
    const wefm_cad::CadModel m = strip_model(narrow_arm_strip(arm.a, arm.b, 0.05), "hand-made strip with a narrow arm");
    const auto nodes = wefm_cad::discretise_model_edges(m, arm.h, std::vector<double>(1, arm.h), 0.3);
    for (long long side : {1LL, 3LL}) {
      CAPTURE(side);
      const double longest = longest_between(nodes.at(side).xyz, arm.x0, arm.x1);
      CHECK(longest > arm.shortest);
      CHECK(longest < arm.longest);
      // The arm's segments and the grading back to h on either side, not thousands.
      CHECK(nodes.at(side).xyz.size() / 3 < 400);
    }
  }
}

TEST_CASE("beside a cusp, a narrow arm far narrower than the cusp's wedge is still sized by its width") {
  // The arm 0.01 across, and a 9-degree cusp at its end (x = 55): within h / 2 of a cusp the width
  // rule leaves the edges to the cusp's fan, which grows as the wedge widens; the arm does not widen
  // (nodeocc_kuka's plate 418 at 1/20: segments of 5 to 10 along an arm 0.03 wide).
  const wefm_cad::CadModel m = strip_model(narrow_arm_strip(40, 55, 0.01), "hand-made strip with a narrow arm beside a cusp");
  const double h = 10;
  wefm_cad::Cusp cusp;
  cusp.point = {55.0, 0.0, 0.0};
  cusp.degrees = 9;
  const auto nodes = wefm_cad::discretise_model_edges(m, h, std::vector<double>(1, h), 0.3, {cusp});
  for (long long side : {1LL, 3LL}) {
    CAPTURE(side);
    const double longest = longest_between(nodes.at(side).xyz, 50, 52.3);
    // The arm's segments (200 over its 15 at most) up to the last size sample (h / 4 apart) that is
    // within the cusp's wedge, not segments growing from 2.5 back beside it.
    CHECK(longest > 0);
    CHECK(longest < 0.1);
  }
}

TEST_CASE("the two edges of a cusp get the same first segment, then a fan growing with the width across") {
  // A triangle with a 5 degree corner at the origin, sides 100 along x and to (100, 100 tan 5), at
  // h = 10. The corner is a cusp: its first segment (no triangle there can reach Lo lambda 0.3) is
  // the same on both edges, so the tip triangle is isosceles, its best; behind it the segments grow
  // by 2.5 times the width across the corner (2 d sin 2.5 at d from the tip), so the triangles across
  // keep their shape, instead of segments of about h along a wedge a fraction of h wide.
  const double degrees = 5, tip = std::tan(degrees * kPi / 180);
  BRepBuilderAPI_MakePolygon outline(gp_Pnt(0, 0, 0), gp_Pnt(100, 0, 0), gp_Pnt(100, 100 * tip, 0), true);
  const wefm_cad::CadModel m = load_shape(BRepBuilderAPI_MakeFace(outline.Wire()).Face(), "wefm_cusp_triangle.brep");
  REQUIRE(m.faces.size() == 1);
  const double h = 10;
  const std::vector<double> sizes(1, h);
  const std::vector<wefm_cad::Cusp> cusps = {{{0.0, 0.0, 0.0}, degrees}};
  const auto fan = wefm_cad::discretise_model_edges(m, h, sizes, 0.3, cusps);
  // Distances from the tip of an edge's nodes that leaves it, in order; empty for the far side.
  auto from_tip = [](const wefm_cad::EdgeNodes& e) {
    std::vector<double> d;
    const size_t n = e.xyz.size() / 3;
    for (size_t k = 0; k < n; ++k) d.push_back(std::hypot(e.xyz[3 * k], e.xyz[3 * k + 1], e.xyz[3 * k + 2]));
    if (d.front() > 1e-9) std::reverse(d.begin(), d.end());
    return d.front() > 1e-9 ? std::vector<double>{} : d;
  };
  std::vector<double> firsts;
  int sides = 0;
  for (const auto& [id, e] : fan) {
    const std::vector<double> d = from_tip(e);
    if (d.empty()) continue;
    ++sides;
    CAPTURE(id);
    REQUIRE(d.size() > 3);
    firsts.push_back(d[1]);
    const double half = std::sin(0.5 * degrees * kPi / 180);
    int fanned = 0;
    // The fan's first segments (where it meets the edge's own sizes, graded by the width as sampled
    // along the edge, a segment may be up to about twice the fan's).
    for (size_t k = 1; k < 5 && k + 1 < d.size(); ++k) {
      const double step = d[k + 1] - d[k], width = 2 * d[k] * half;
      CAPTURE(k);
      CHECK(step == doctest::Approx(2.5 * width).epsilon(0.01));
      ++fanned;
    }
    CHECK(fanned == 4);
  }
  CHECK(sides == 2);
  REQUIRE(firsts.size() == 2);
  CHECK(firsts[0] == doctest::Approx(firsts[1]).epsilon(1e-9));
}

TEST_CASE("a cusp's fan goes on along the next edge where a side of the corner is a single segment") {
  // The 5 degree triangle of the test above, its upper side split 2 from the tip: the tip's short
  // edge is the side's first segment (the vertex's size), and the long edge after it carries on the
  // fan from 2 behind its start, as one edge would. Else its segments there keep about its own
  // spacing over a wedge a fraction of that wide.
  const double degrees = 5, rad = degrees * kPi / 180;
  BRepBuilderAPI_MakePolygon outline;
  for (const gp_Pnt& p : {gp_Pnt(0, 0, 0), gp_Pnt(100, 0, 0), gp_Pnt(100, 100 * std::tan(rad), 0), gp_Pnt(2 * std::cos(rad), 2 * std::sin(rad), 0)})
    outline.Add(p);
  outline.Close();
  const wefm_cad::CadModel m = load_shape(BRepBuilderAPI_MakeFace(outline.Wire()).Face(), "wefm_cusp_split_side.brep");
  REQUIRE(m.faces.size() == 1);
  REQUIRE(m.faces[0].edges.size() == 4);
  const double h = 10;
  // The model edge ids of the tip's short side and of the long edge after it, by their ends.
  long long tip_side = -1, long_side = -1, bottom = -1;
  for (const wefm_cad::CadEdge& e : m.faces[0].edges) {
    const double* a = &m.faces[0].xyz[3 * static_cast<size_t>(e.vertices.front())];
    const double* b = &m.faces[0].xyz[3 * static_cast<size_t>(e.vertices.back())];
    const bool at_tip = std::hypot(a[0], a[1]) < 1e-9 || std::hypot(b[0], b[1]) < 1e-9;
    const bool far = a[0] > 99 || b[0] > 99;
    if (at_tip && far) bottom = e.id;
    else if (at_tip) tip_side = e.id;
    else if (std::hypot(a[0], a[1]) < 3 || std::hypot(b[0], b[1]) < 3) long_side = e.id;
  }
  REQUIRE(tip_side >= 0);
  REQUIRE(long_side >= 0);
  REQUIRE(bottom >= 0);
  wefm_cad::Cusp cusp{{0.0, 0.0, 0.0}, degrees, {tip_side, bottom}, {long_side, -1}};
  const auto nodes = wefm_cad::discretise_model_edges(m, h, std::vector<double>(1, h), 0.3, {cusp});
  REQUIRE(nodes.at(tip_side).xyz.size() == 6);  // a single segment
  // Distances from the tip of the long side's nodes, from its end at the short side on.
  const std::vector<double>& x = nodes.at(long_side).xyz;
  std::vector<double> d;
  for (size_t k = 0; k < x.size() / 3; ++k) d.push_back(std::hypot(x[3 * k], x[3 * k + 1], x[3 * k + 2]));
  if (d.front() > d.back()) std::reverse(d.begin(), d.end());
  REQUIRE(d.front() == doctest::Approx(2.0).epsilon(1e-6));
  REQUIRE(d.size() > 6);
  for (size_t k = 0; k < 4; ++k) {
    CAPTURE(k);
    CHECK(d[k + 1] - d[k] == doctest::Approx(2.5 * 2 * d[k] * std::sin(0.5 * rad)).epsilon(0.01));
  }
}

TEST_CASE("a face bounded by an arc and its chord keeps an area at any size: three segments at least") {
  // A circular segment: an arc of radius 10 over 40 degrees and its chord (6.84 long, 0.60 high).
  // At h = 1000 each edge would be one segment, the arc's the same line as the chord: a face of no
  // area, whose mesh collapses and leaves its neighbours' edges open.
  const gp_Circ circle(gp_Ax2(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), 10.0);
  const double a = 20 * kPi / 180;
  const gp_Pnt p(10 * std::cos(a), -10 * std::sin(a), 0), q(10 * std::cos(a), 10 * std::sin(a), 0);
  const TopoDS_Edge arc = BRepBuilderAPI_MakeEdge(circle, p, q).Edge();
  const TopoDS_Edge chord = BRepBuilderAPI_MakeEdge(q, p).Edge();
  const TopoDS_Face face = BRepBuilderAPI_MakeFace(BRepBuilderAPI_MakeWire(arc, chord).Wire()).Face();
  const wefm_cad::CadModel m = load_shape(face, "wefm_circular_segment.brep");
  REQUIRE(m.faces.size() == 1);
  REQUIRE(m.faces[0].edges.size() == 2);
  for (double g : {0.0, 0.3}) {
    CAPTURE(g);
    const double h = 1000;
    const auto nodes = g > 0 ? wefm_cad::discretise_model_edges(m, h, wefm_cad::local_face_sizes(m, h), g) : wefm_cad::discretise_model_edges(m, h);
    size_t segments = 0;
    for (const auto& [id, e] : nodes) segments += e.xyz.size() / 3 - 1;
    CHECK(segments >= 3);
    CHECK(segments <= 4);
  }
}

TEST_CASE("two edges lying on each other bound a closed surface, not a face of width zero") {
  // A tube of radius 10 and length 100 tessellated by hand (48 facets round, 20 along) and cut
  // open along a line as two edges of their own (ids 2 and 4), where a seam would be one edge used
  // twice: IGES files bound closed B-spline surfaces so (pyocc_surf114.igs in shared/data/cad-more). The face is 2 pi 10 wide across the cut,
  // not 0: at h = 20 (size 10, the radius) each cut edge gets about 10 segments, not the
  // narrow-face floor of h / 32 (160 segments, and a face of tens of thousands of triangles).
  constexpr int kRound = 48, kAlong = 20;
  wefm_cad::CadModel m;
  m.path = "hand-made tube";
  m.format = "brep";
  m.bbox_diagonal = std::sqrt(20.0 * 20.0 * 2 + 100.0 * 100.0);
  m.linear_deflection = 1e-3 * m.bbox_diagonal;
  CadFace f;
  f.index = 1;
  f.surface_type = "bspline";
  auto id = [](int i, int j) { return static_cast<int32_t>(i * (kRound + 1) + j); };
  // The cut's second edge lies a hair past the first (a two-millionth of the diagonal), on the
  // face's side of it: one curve's points computed twice.
  const double past = 0.5e-6 * m.bbox_diagonal / 10;
  for (int i = 0; i <= kAlong; ++i)
    for (int j = 0; j <= kRound; ++j) {
      const double a = 2 * kPi * j / kRound + (j == kRound ? past : 0.0);
      f.xyz.insert(f.xyz.end(), {10 * std::cos(a), 10 * std::sin(a), 100.0 * i / kAlong});
    }
  for (int i = 0; i < kAlong; ++i)
    for (int j = 0; j < kRound; ++j)
      f.triangles.insert(f.triangles.end(), {id(i, j), id(i, j + 1), id(i + 1, j + 1), id(i, j), id(i + 1, j + 1), id(i + 1, j)});
  auto chain = [&](long long edge_id, int i0, int j0, int di, int dj, int n) {
    wefm_cad::CadEdge e;
    e.id = edge_id;
    e.curve_type = "BSplineCurve";
    for (int k = 0; k <= n; ++k) e.vertices.push_back(id(i0 + k * di, j0 + k * dj));
    return e;
  };
  f.edges = {chain(1, 0, 0, 0, 1, kRound), chain(2, 0, kRound, 1, 0, kAlong), chain(3, kAlong, kRound, 0, -1, kRound),
             chain(4, kAlong, 0, -1, 0, kAlong)};
  f.loops = {{{0, false}, {1, false}, {2, false}, {3, false}}};
  f.outer_loop = 0;
  m.faces.push_back(f);
  m.edge_count = 4;

  const double h = 20;
  const std::vector<double> sizes = wefm_cad::local_face_sizes(m, h);
  REQUIRE(sizes.size() == 1);
  CHECK(sizes[0] == doctest::Approx(10.0).epsilon(0.05));
  const auto nodes = wefm_cad::discretise_model_edges(m, h, sizes, 0.3);
  for (long long cut : {2LL, 4LL}) {
    CAPTURE(cut);
    REQUIRE(nodes.count(cut));
    const size_t segments = nodes.at(cut).xyz.size() / 3 - 1;
    CHECK(segments >= 8);
    CHECK(segments <= 15);
  }
}

TEST_CASE("a face's radius of curvature is not set by the needle facets along its edges") {
  // A quarter of a tube of radius 100, 100 long, tessellated by hand (30 x 20 cells), with a strip
  // 0.01 high along its lower edge fanned into 600 needles whose lower corners zigzag 0.001 in and
  // out, as a tessellator leaves along the edges of freeform faces. The needles bend by tenths of a
  // radian over thousandths: radii of a hundredth, on a quarter of the facet edges. By area they
  // are nothing: the face is a gentle curve and gets h (20), not the h / 8 floor.
  constexpr int kRound = 30, kAlong = 20, kNeedles = 20;  // needles per cell of the lower row
  constexpr double kR = 100, kTurn = kPi / 2;
  wefm_cad::CadModel m;
  m.path = "hand-made quarter tube";
  m.format = "brep";
  m.bbox_diagonal = std::sqrt(3 * 100.0 * 100.0);
  m.linear_deflection = 1e-3 * m.bbox_diagonal;
  CadFace f;
  f.index = 1;
  f.surface_type = "bspline";
  auto add = [&](double a, double z, double r) {
    f.xyz.insert(f.xyz.end(), {r * std::cos(a), r * std::sin(a), z});
    return static_cast<int32_t>(f.xyz.size() / 3 - 1);
  };
  std::vector<int32_t> grid, low;
  for (int i = 0; i <= kAlong; ++i)
    for (int j = 0; j <= kRound; ++j) grid.push_back(add(kTurn * j / kRound, 100.0 * i / kAlong, kR));
  for (int k = 0; k <= kRound * kNeedles; ++k) low.push_back(add(kTurn * k / (kRound * kNeedles), -0.01, kR + (k % 2 ? 1e-3 : 0.0)));
  auto g = [&](int i, int j) { return grid[static_cast<size_t>(i * (kRound + 1) + j)]; };
  for (int i = 0; i < kAlong; ++i)
    for (int j = 0; j < kRound; ++j) f.triangles.insert(f.triangles.end(), {g(i, j), g(i, j + 1), g(i + 1, j + 1), g(i, j), g(i + 1, j + 1), g(i + 1, j)});
  for (int j = 0; j < kRound; ++j) {
    for (int k = j * kNeedles; k < (j + 1) * kNeedles; ++k)
      f.triangles.insert(f.triangles.end(), {low[static_cast<size_t>(k)], low[static_cast<size_t>(k + 1)], g(0, j)});
    f.triangles.insert(f.triangles.end(), {low[static_cast<size_t>((j + 1) * kNeedles)], g(0, j + 1), g(0, j)});
  }
  wefm_cad::CadEdge bottom, right, top, left;
  bottom.vertices = low;
  right.vertices.push_back(low.back());
  for (int i = 0; i <= kAlong; ++i) right.vertices.push_back(g(i, kRound));
  for (int j = kRound; j >= 0; --j) top.vertices.push_back(g(kAlong, j));
  for (int i = kAlong; i >= 0; --i) left.vertices.push_back(g(i, 0));
  left.vertices.push_back(low.front());
  long long next_id = 1;
  for (wefm_cad::CadEdge* e : {&bottom, &right, &top, &left}) {
    e->id = next_id++;
    e->curve_type = "BSplineCurve";
    f.edges.push_back(*e);
  }
  f.loops = {{{0, false}, {1, false}, {2, false}, {3, false}}};
  f.outer_loop = 0;
  m.faces.push_back(f);
  m.edge_count = 4;
  const std::vector<double> sizes = wefm_cad::local_face_sizes(m, 20.0);
  REQUIRE(sizes.size() == 1);
  CHECK(sizes[0] == 20.0);
}

TEST_CASE("unreadable and unknown files are reported, not thrown") {
  wefm_cad::CadModel m;
  std::string error;
  CHECK_FALSE(wefm_cad::load_cad_model(WEFM_TEST_DATA "/no_such_file.step", {}, m, error));
  CHECK(error.find("no_such_file") != std::string::npos);
  CHECK_FALSE(wefm_cad::load_cad_model(WEFM_TEST_DATA "/pyramid5.obj", {}, m, error));
  CHECK(error.find("unknown CAD format") != std::string::npos);
}
