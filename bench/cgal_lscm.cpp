// wefm-bench-cgal: the peer in the benchmark. Times CGAL's LSCM (Surface_mesh_parameterization::
// LSCM_parameterizer_3, default solver) on the same generated faces as wefm-bench and prints one
// JSON line; wefm-bench runs it as a child process per case and divides its own times by it.
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_parameterization/LSCM_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/parameterize.h>

#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cgal_errors.hpp"
#include "face_generator.hpp"
#include "process_stats.hpp"

namespace SMP = CGAL::Surface_mesh_parameterization;
using Kernel = CGAL::Simple_cartesian<double>;
using SurfaceMesh = CGAL::Surface_mesh<Kernel::Point_3>;
using VertexIndex = SurfaceMesh::Vertex_index;

int main(int argc, char** argv) {
  using wefm_bench::now_seconds;
  if (argc != 4 || std::string(argv[1]) != "--case") {
    std::fprintf(stderr, "usage: wefm-bench-cgal --case SHAPE SIZE   (run by wefm-bench)\n");
    return 2;
  }
  wefm_bench::Shape shape;
  int64_t size = 0;
  if (!wefm_bench::parse_shape(argv[2], shape) || !wefm_bench::parse_size(argv[3], size)) {
    std::fprintf(stderr, "wefm-bench-cgal: bad shape or size\n");
    return 2;
  }
  // Cut along its seam, if it has one: LSCM needs a topological disk.
  const wefm_bench::Face f = wefm_bench::generate(shape, size, true);
  nlohmann::ordered_json j;
  j["kind"] = "cgal";
  j["shape"] = wefm_bench::shape_name(shape);
  j["size"] = wefm_bench::size_label(size);
  j["vertices"] = f.vertices();
  j["triangles"] = f.triangles();
  j["cgal_version"] = CGAL_VERSION_STR;

  double t = now_seconds();
  SurfaceMesh sm;
  sm.reserve(static_cast<SurfaceMesh::size_type>(f.vertices()), static_cast<SurfaceMesh::size_type>(3 * f.triangles() / 2 + f.vertices()),
             static_cast<SurfaceMesh::size_type>(f.triangles()));
  std::vector<VertexIndex> v;
  v.reserve(static_cast<size_t>(f.vertices()));
  for (int64_t i = 0; i < f.vertices(); ++i) {
    const size_t k = static_cast<size_t>(3 * i);
    v.push_back(sm.add_vertex(Kernel::Point_3(f.xyz[k], f.xyz[k + 1], f.xyz[k + 2])));
  }
  for (int64_t i = 0; i < f.triangles(); ++i) {
    const size_t k = static_cast<size_t>(3 * i);
    sm.add_face(v[static_cast<size_t>(f.tri[k])], v[static_cast<size_t>(f.tri[k + 1])], v[static_cast<size_t>(f.tri[k + 2])]);
  }
  // LSCM pins two vertices of the border it is given; give it the outer (longest) one.
  const auto border = CGAL::Polygon_mesh_processing::longest_border(sm).first;
  auto uv = sm.add_property_map<VertexIndex, Kernel::Point_2>("v:uv").first;
  j["time_build"] = now_seconds() - t;

  t = now_seconds();
  const double c0 = wefm_bench::cpu_seconds();
  const SMP::Error_code err = SMP::parameterize(sm, SMP::LSCM_parameterizer_3<SurfaceMesh>(), border, uv);
  j["time_parameterize"] = now_seconds() - t;
  j["cpu_parameterize"] = wefm_bench::cpu_seconds() - c0;
  j["status"] = err == SMP::OK ? std::string("ok") : std::string("CGAL error: ") + wefm_bench::cgal_error_name(err);
  j["peak_rss_mb"] = wefm_bench::peak_rss_mb();
  std::printf("%s\n", j.dump().c_str());
  return 0;
}
