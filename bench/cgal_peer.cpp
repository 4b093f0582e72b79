// wefm-peer-cgal: CGAL's surface parameterizations of one face, for the peer comparison of
// bench/compare_peers.py (docs/RESULTS.md, "Against other flatteners"). Reads a triangulated face
// (OBJ/OFF/STL/PLY through the library's own reader, wefm_mesh_read), builds a CGAL Surface_mesh,
// runs one or more methods of CGAL's Surface_mesh_parameterization package on its longest border
// and writes each layout as an OBJ with v (3D), one vt per vertex and f v/vt, plus one JSON line per
// method on stdout (status, CGAL's error code, wall and CPU time of the parameterize call).
//
// Methods (CGAL 5.5 defaults unless stated):
//   lscm  LSCM_parameterizer_3: free border, two vertices pinned (Two_vertices_parameterizer_3: the
//         extreme vertices along the longest bounding-box axis); Eigen SimplicialLDLT.
//   arap  ARAP_parameterizer_3: Liu et al.'s local/global method, lambda 1000, at most 50
//         iterations, started from LSCM; MVC post-processing when the result is not one-to-one.
//   dcm   Discrete_conformal_map_parameterizer_3: border fixed on a circle (arc length).
//   mvc   Mean_value_coordinates_parameterizer_3: border fixed on a circle (arc length).
//
// CGAL's package requires a topological disk. A face with several boundary loops is still run
// (CGAL does not check; "boundary_loops" in the JSON says so), a closed face or one with several
// components is refused. This program is a benchmark, built only when CGAL is found; the library
// never links CGAL.
//
// Exit codes: 0 every method returned OK (the layout may still have flips: that is the checker's
// business), 1 a method returned a CGAL error or threw, 2 usage, 3 input unreadable or not a mesh
// CGAL can take, 4 an output file could not be written.
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_parameterization/ARAP_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Discrete_conformal_map_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/LSCM_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Mean_value_coordinates_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/parameterize.h>
#include <CGAL/version.h>
#include <wefm/wefm.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cgal_errors.hpp"
#include "process_stats.hpp"

#ifndef CGAL_EIGEN3_ENABLED
#error "wefm-peer-cgal needs CGAL_EIGEN3_ENABLED (CGAL::Eigen3_support): CGAL's default solvers are Eigen's"
#endif

namespace {

namespace SMP = CGAL::Surface_mesh_parameterization;
using Kernel = CGAL::Simple_cartesian<double>;
using SurfaceMesh = CGAL::Surface_mesh<Kernel::Point_3>;
using VertexIndex = SurfaceMesh::Vertex_index;
using HalfedgeIndex = SurfaceMesh::Halfedge_index;
using UvMap = SurfaceMesh::Property_map<VertexIndex, Kernel::Point_2>;

const char* const kMethods[] = {"lscm", "arap", "dcm", "mvc"};


void usage(FILE* to) {
  std::fprintf(to,
               "usage: wefm-peer-cgal FACE.obj -o PREFIX [--method lscm,arap,dcm,mvc|all]\n"
               "                      [--arap-lambda L] [--arap-iterations N]\n"
               "Runs CGAL %s Surface_mesh_parameterization methods on the face (a topological disk:\n"
               "cut seams open first) and writes PREFIX.METHOD.obj (v, vt, f v/vt) for each, with one\n"
               "JSON line per method on stdout. Exit: 0 all OK, 1 a CGAL error or exception, 2 usage,\n"
               "3 bad input, 4 cannot write.\n",
               CGAL_VERSION_STR);
}

struct Input {
  std::vector<double> xyz;
  std::vector<int32_t> tri;
  wefm_mesh_info info{};
};

// Reads the file through the library's C API; returns an empty string or the reason it failed.
std::string read_input(const std::string& path, Input& in) {
  wefm_mesh* mesh = nullptr;
  wefm_status st = wefm_mesh_read(path.c_str(), 0.0, &mesh);
  if (st != WEFM_OK) return std::string(wefm_status_string(st)) + ": " + wefm_last_error();
  int64_t n = 0;
  std::string err;
  wefm_mesh_info_init(&in.info, sizeof in.info);
  if ((st = wefm_mesh_get_vertices(mesh, nullptr, 0, &n)) == WEFM_OK) {
    in.xyz.resize(static_cast<size_t>(n));
    st = wefm_mesh_get_vertices(mesh, in.xyz.data(), n, &n);
  }
  if (st == WEFM_OK && (st = wefm_mesh_get_triangles(mesh, nullptr, 0, &n)) == WEFM_OK) {
    in.tri.resize(static_cast<size_t>(n));
    st = wefm_mesh_get_triangles(mesh, in.tri.data(), n, &n);
  }
  if (st == WEFM_OK) st = wefm_mesh_get_info(mesh, &in.info);
  if (st != WEFM_OK) err = std::string(wefm_status_string(st)) + ": " + wefm_last_error();
  wefm_mesh_release(mesh);
  return err;
}

// The Surface_mesh, vertices in file order; empty string or why CGAL cannot take the mesh.
std::string build_mesh(const Input& in, SurfaceMesh& sm) {
  const size_t nv = in.xyz.size() / 3, nt = in.tri.size() / 3;
  if (nt == 0) return "no triangles";
  if (in.info.components != 1)
    return std::to_string(in.info.components) + " connected components (CGAL parameterizes a single disk)";
  if (in.info.boundary_loops == 0) return "closed surface, no boundary (CGAL needs a disk: cut it open first)";
  if (in.info.non_manifold_edges != 0 || in.info.non_manifold_vertices != 0 || in.info.inconsistent_edges != 0)
    return "non-manifold or inconsistently oriented mesh";
  std::vector<VertexIndex> v;
  v.reserve(nv);
  sm.reserve(static_cast<SurfaceMesh::size_type>(nv), static_cast<SurfaceMesh::size_type>(3 * nt / 2 + nv),
             static_cast<SurfaceMesh::size_type>(nt));
  for (size_t i = 0; i < nv; ++i) v.push_back(sm.add_vertex(Kernel::Point_3(in.xyz[3 * i], in.xyz[3 * i + 1], in.xyz[3 * i + 2])));
  for (size_t t = 0; t < nt; ++t) {
    const auto f = sm.add_face(v[static_cast<size_t>(in.tri[3 * t])], v[static_cast<size_t>(in.tri[3 * t + 1])],
                               v[static_cast<size_t>(in.tri[3 * t + 2])]);
    if (f == SurfaceMesh::null_face()) return "CGAL Surface_mesh refused triangle " + std::to_string(t) + " (non-manifold)";
  }
  return "";
}

bool write_layout(const std::string& path, const SurfaceMesh& sm, const UvMap& uv) {
  FILE* f = std::fopen(path.c_str(), "w");
  if (!f) return false;
  std::fprintf(f, "# wefm-peer-cgal layout: v = 3D, vt = UV (one per vertex), f v/vt\n");
  for (const VertexIndex vi : sm.vertices()) {
    const auto& p = sm.point(vi);
    std::fprintf(f, "v %.17g %.17g %.17g\n", p.x(), p.y(), p.z());
  }
  for (const VertexIndex vi : sm.vertices()) std::fprintf(f, "vt %.17g %.17g\n", uv[vi].x(), uv[vi].y());
  for (const auto fi : sm.faces()) {
    std::fprintf(f, "f");
    for (const VertexIndex vi : CGAL::vertices_around_face(sm.halfedge(fi), sm)) {
      const unsigned k = static_cast<unsigned>(vi) + 1;
      std::fprintf(f, " %u/%u", k, k);
    }
    std::fprintf(f, "\n");
  }
  const bool ok = std::ferror(f) == 0;
  return std::fclose(f) == 0 && ok;
}

struct Settings {
  double arap_lambda = 1000.0;
  unsigned arap_iterations = 50;
};

SMP::Error_code run_method(const std::string& method, const Settings& set, SurfaceMesh& sm, HalfedgeIndex border,
                           UvMap& uv) {
  if (method == "lscm") return SMP::parameterize(sm, SMP::LSCM_parameterizer_3<SurfaceMesh>(), border, uv);
  if (method == "arap") {
    using Arap = SMP::ARAP_parameterizer_3<SurfaceMesh>;
    return SMP::parameterize(
        sm, Arap(Arap::Border_parameterizer(), Arap::Solver_traits(), set.arap_lambda, set.arap_iterations), border, uv);
  }
  if (method == "dcm") return SMP::parameterize(sm, SMP::Discrete_conformal_map_parameterizer_3<SurfaceMesh>(), border, uv);
  return SMP::parameterize(sm, SMP::Mean_value_coordinates_parameterizer_3<SurfaceMesh>(), border, uv);
}

std::vector<std::string> split_methods(const std::string& list, std::string& bad) {
  std::vector<std::string> out;
  if (list == "all") return {std::begin(kMethods), std::end(kMethods)};
  size_t start = 0;
  while (start <= list.size()) {
    const size_t comma = list.find(',', start);
    const std::string m = list.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    bool known = false;
    for (const char* k : kMethods) known = known || m == k;
    if (!known) bad = m;
    out.push_back(m);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  std::string input, prefix, methods_arg = "all";
  Settings set;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc;
    if (a == "-h" || a == "--help") {
      usage(stdout);
      return 0;
    } else if (a == "-o" && has_value) {
      prefix = argv[++i];
    } else if (a == "--method" && has_value) {
      methods_arg = argv[++i];
    } else if (a == "--arap-lambda" && has_value) {
      char* end = nullptr;
      set.arap_lambda = std::strtod(argv[++i], &end);
      if (*end != '\0' || !(set.arap_lambda >= 0.0)) {
        std::fprintf(stderr, "wefm-peer-cgal: --arap-lambda wants a number >= 0\n");
        return 2;
      }
    } else if (a == "--arap-iterations" && has_value) {
      char* end = nullptr;
      const long n = std::strtol(argv[++i], &end, 10);
      if (*end != '\0' || n < 1 || n > 100000) {
        std::fprintf(stderr, "wefm-peer-cgal: --arap-iterations wants an integer in 1..100000\n");
        return 2;
      }
      set.arap_iterations = static_cast<unsigned>(n);
    } else if (!a.empty() && a[0] != '-' && input.empty()) {
      input = a;
    } else {
      std::fprintf(stderr, "wefm-peer-cgal: unexpected argument '%s'\n", a.c_str());
      usage(stderr);
      return 2;
    }
  }
  if (input.empty() || prefix.empty()) {
    usage(stderr);
    return 2;
  }
  std::string bad;
  const std::vector<std::string> methods = split_methods(methods_arg, bad);
  if (!bad.empty()) {
    std::fprintf(stderr, "wefm-peer-cgal: unknown method '%s' (lscm, arap, dcm, mvc or all)\n", bad.c_str());
    return 2;
  }

  nlohmann::ordered_json base;
  base["kind"] = "cgal";
  base["cgal_version"] = CGAL_VERSION_STR;
  base["input"] = input;
  Input in;
  double t = wefm_bench::now_seconds();
  std::string err = read_input(input, in);
  base["time_read"] = wefm_bench::now_seconds() - t;
  SurfaceMesh sm;
  if (err.empty()) {
    base["vertices"] = in.info.vertices;
    base["triangles"] = in.info.triangles;
    base["boundary_loops"] = in.info.boundary_loops;
    base["genus"] = in.info.genus;
    base["degenerate_triangles"] = in.info.degenerate_triangles;
    t = wefm_bench::now_seconds();
    err = build_mesh(in, sm);
    base["time_build"] = wefm_bench::now_seconds() - t;
  }
  if (!err.empty()) {
    for (const std::string& m : methods) {
      nlohmann::ordered_json j = base;
      j["method"] = m;
      j["status"] = "bad input";
      j["message"] = err;
      std::printf("%s\n", j.dump().c_str());
    }
    std::fprintf(stderr, "wefm-peer-cgal: %s: %s\n", input.c_str(), err.c_str());
    return 3;
  }
  // Every method gets the longest border (the outer loop of a face with holes); CGAL's LSCM and
  // ARAP pin their two vertices on it, the fixed-border methods put it on the circle.
  const HalfedgeIndex border = CGAL::Polygon_mesh_processing::longest_border(sm).first;
  if (in.info.boundary_loops > 1)
    base["note"] = std::to_string(in.info.boundary_loops) +
                   " boundary loops: CGAL's Surface_mesh_parameterization requires a topological disk (not checked by "
                   "CGAL; run on the longest border, the other loops are left free)";

  int rc = 0;
  for (const std::string& m : methods) {
    nlohmann::ordered_json j = base;
    j["method"] = m;
    UvMap uv = sm.add_property_map<VertexIndex, Kernel::Point_2>("v:uv", Kernel::Point_2(0, 0)).first;
    for (const VertexIndex vi : sm.vertices()) uv[vi] = Kernel::Point_2(0, 0);
    SMP::Error_code code = SMP::OK;
    std::string exception;
    t = wefm_bench::now_seconds();
    const double c0 = wefm_bench::cpu_seconds();
    try {
      code = run_method(m, set, sm, border, uv);
    } catch (const std::exception& e) {
      exception = e.what();
    } catch (...) {
      exception = "unknown exception";
    }
    j["time_parameterize"] = wefm_bench::now_seconds() - t;
    j["cpu_parameterize"] = wefm_bench::cpu_seconds() - c0;
    int64_t non_finite = 0;
    for (const VertexIndex vi : sm.vertices())
      if (!std::isfinite(uv[vi].x()) || !std::isfinite(uv[vi].y())) ++non_finite;
    j["non_finite_uv"] = non_finite;
    if (!exception.empty()) {
      j["status"] = "exception";
      j["message"] = exception;
      rc = rc == 0 ? 1 : rc;
    } else if (code != SMP::OK) {
      j["status"] = "cgal error";
      j["message"] = wefm_bench::cgal_error_name(code);
      rc = rc == 0 ? 1 : rc;
    } else {
      j["status"] = non_finite ? "non-finite uv" : "ok";
      if (non_finite) rc = rc == 0 ? 1 : rc;
    }
    // A layout is written whenever CGAL returned one, also after an error, so the checker can say
    // what it looks like; "status" says whether CGAL considered it a success.
    const std::string out = prefix + "." + m + ".obj";
    t = wefm_bench::now_seconds();
    if (write_layout(out, sm, uv)) {
      j["output"] = out;
    } else {
      j["output"] = nullptr;
      j["write_error"] = "cannot write " + out;
      std::fprintf(stderr, "wefm-peer-cgal: cannot write %s\n", out.c_str());
      rc = 4;
    }
    j["time_write"] = wefm_bench::now_seconds() - t;
    j["peak_rss_mb"] = wefm_bench::peak_rss_mb();
    std::printf("%s\n", j.dump().c_str());
    std::fflush(stdout);
    sm.remove_property_map(uv);
  }
  return rc;
}
