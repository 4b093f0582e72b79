#include "case_runner.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>

#include <sys/stat.h>
#include <unistd.h>

#include "laplacian_floor.hpp"
#include "mesh_formats.hpp"
#include "process_stats.hpp"
#include "wefm/wefm.h"

namespace wefm_bench {

namespace {

Json face_header(const char* kind, Shape shape, int64_t size, const Face& f) {
  Json j;
  j["kind"] = kind;
  j["shape"] = shape_name(shape);
  j["size"] = size_label(size);
  j["vertices"] = f.vertices();
  j["triangles"] = f.triangles();
  return j;
}

Json number(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

// Wall time spent in each progress stage: from the callback naming it to the next callback naming
// another stage. Independent of the report's own timers, so it also shows what they leave out.
// CPU time per stage too: on a shared machine the wall clock also counts waiting for a core.
struct StageClock {
  std::map<std::string, double> seconds, cpu;
  std::string current;
  double since = 0, cpu_since = 0;
  static int callback(void* self, double, const char* stage) {
    auto* c = static_cast<StageClock*>(self);
    const double t = now_seconds(), tc = cpu_seconds();
    if (c->current != stage) {
      if (!c->current.empty()) {
        c->seconds[c->current] += t - c->since;
        c->cpu[c->current] += tc - c->cpu_since;
      }
      c->current = stage;
      c->since = t;
      c->cpu_since = tc;
    }
    return 0;
  }
  void finish() {
    if (!current.empty() && current != "done") {
      seconds[current] += now_seconds() - since;
      cpu[current] += cpu_seconds() - cpu_since;
    }
    current.clear();
  }
};

}  // namespace

Json run_wefm_case(Shape shape, int64_t size, double s, int threads) {
  double t = now_seconds();
  const Face f = generate(shape, size);
  Json j = face_header("wefm", shape, size, f);
  j["s"] = s;
  j["threads"] = threads;
  j["time_generate"] = now_seconds() - t;
  wefm_face* face = nullptr;
  if (wefm_face_create(&face) != WEFM_OK) {
    j["status"] = "WEFM_ERROR_OUT_OF_MEMORY";
    return j;
  }
  wefm_options o;
  wefm_options_init(&o);
  o.s = s;
  o.threads = threads;
  StageClock clock;
  const double cpu0 = cpu_seconds();
  t = now_seconds();
  wefm_status st = wefm_face_set_mesh(face, f.vertices(), f.xyz.data(), f.triangles(), f.tri.data());
  if (st == WEFM_OK && !f.seam.empty()) st = wefm_face_add_seams(face, static_cast<int64_t>(f.seam.size() / 2), f.seam.data());
  const double t_set = now_seconds();
  if (st == WEFM_OK) st = wefm_face_set_options(face, &o);
  if (st == WEFM_OK) st = wefm_face_build(face);
  const double t_build = now_seconds();
  const double rss_before = current_rss_mb();
  if (st == WEFM_OK) {
    wefm_face_set_progress_callback(face, &StageClock::callback, &clock);
    st = wefm_face_solve(face);
    clock.finish();
  }
  const double t_solve = now_seconds();
  j["cpu_library"] = cpu_seconds() - cpu0;
  j["status"] = wefm_status_string(st);
  if (st != WEFM_OK) j["message"] = wefm_face_last_error(face);
  j["time_set_mesh"] = t_set - t;
  j["time_build"] = t_build - t_set;
  j["time_solve_wall"] = t_solve - t_build;
  j["time_library"] = t_solve - t;  // everything the library did with the arrays
  j["rss_before_solve_mb"] = rss_before;
  int32_t solved = 0;
  wefm_face_has_result(face, &solved);
  if (solved) {
    wefm_report r;
    wefm_report_init(&r);
    wefm_face_get_report(face, &r);
    j["report"] = {{"score", number(r.score)},
                   {"flipped_triangles", r.flipped_triangles},
                   {"s_reached", r.s},
                   {"converged", r.converged != 0},
                   {"s_steps", r.s_steps},
                   {"rho_iterations", r.rho_iterations},
                   {"symbolic_analyses", r.symbolic_analyses},
                   {"numeric_factorizations", r.numeric_factorizations},
                   {"solves", r.solves},
                   {"iterative_iterations", r.iterative_iterations},
                   {"time_topology", r.time_topology},
                   {"time_coefficients", r.time_coefficients},
                   {"time_assembly", r.time_assembly},
                   {"time_analysis", r.time_analysis},
                   {"time_factorization", r.time_factorization},
                   {"time_solve", r.time_solve},
                   {"time_continuation", r.time_continuation},
                   {"time_quality", r.time_quality},
                   {"time_total", r.time_total},
                   {"peak_memory_mb", r.peak_memory_mb}};
  }
  Json stages = Json::object(), stages_cpu = Json::object();
  for (const auto& [name, sec] : clock.seconds) stages[name] = sec;
  for (const auto& [name, sec] : clock.cpu) stages_cpu[name] = sec;
  j["progress_stages"] = stages;
  j["progress_stages_cpu"] = stages_cpu;
  wefm_face_release(face);
  j["peak_rss_mb"] = peak_rss_mb();
  return j;
}

Json run_floor_case(Shape shape, int64_t size, bool complex_arithmetic) {
  const Face f = generate(shape, size);
  Json j = face_header(complex_arithmetic ? "floor_complex" : "floor", shape, size, f);
  const double rss_before = current_rss_mb();
  const double cpu0 = cpu_seconds();
  const FloorResult r = measure_floor(f, complex_arithmetic);
  j["cpu_floor_with_assembly"] = cpu_seconds() - cpu0;
  j["status"] = r.ok ? "ok" : r.error;
  j["n"] = r.n;
  j["matrix_nnz"] = r.matrix_nnz;
  j["factor_nnz"] = r.factor_nnz;
  j["flops"] = r.flops;
  j["ordering"] = r.ordering;
  j["time_assembly"] = r.assembly;
  j["time_analysis"] = r.analysis;
  j["time_factorization"] = r.factorization;
  j["time_solve"] = r.solve;
  j["time_floor"] = r.total();
  j["cpu_floor"] = r.cpu;
  j["rss_before_mb"] = rss_before;
  j["peak_rss_mb"] = peak_rss_mb();
  return j;
}

Json run_io_case(Shape shape, int64_t size, const std::string& work_dir) {
  const Face f = generate(shape, size);
  Json j = face_header("io", shape, size, f);
  const std::string base = work_dir + "/wefm-bench-io-" + std::to_string(getpid()) + "-" + shape_name(shape) + "_" + size_label(size);
  auto file_mb = [](const std::string& path) {
    struct stat st {};
    return ::stat(path.c_str(), &st) == 0 ? static_cast<double>(st.st_size) / (1024.0 * 1024.0) : 0.0;
  };
  // Wall and CPU time of one step; CPU time is what to compare on a busy machine.
  auto timed = [&](const char* name, auto&& step) {
    const double w = now_seconds(), c = cpu_seconds();
    step();
    j[std::string("time_") + name] = now_seconds() - w;
    j[std::string("cpu_") + name] = cpu_seconds() - c;
  };
  const std::string obj = base + ".obj", stl = base + ".stl", uv = base + "_uv.obj";
  bool ok = true;
  timed("generator_write_obj", [&] { ok = ok && write_obj(obj, f); });
  timed("generator_write_stl", [&] { ok = ok && write_stl(stl, f); });
  if (!ok) {
    j["status"] = "cannot write in " + work_dir + ": " + std::strerror(errno);
    return j;
  }
  j["obj_mb"] = file_mb(obj);
  j["stl_mb"] = file_mb(stl);
  std::string status = "ok";
  wefm_mesh* mesh = nullptr;
  timed("read_obj", [&] {
    if (wefm_mesh_read(obj.c_str(), 0.0, &mesh) != WEFM_OK) status = std::string("OBJ: ") + wefm_last_error();
  });
  wefm_mesh_release(mesh);
  mesh = nullptr;
  timed("read_stl", [&] {
    if (wefm_mesh_read(stl.c_str(), 0.0, &mesh) != WEFM_OK) status = std::string("STL: ") + wefm_last_error();
  });
  if (mesh) {
    wefm_mesh_info info;
    wefm_mesh_info_init(&info);
    if (wefm_mesh_get_info(mesh, &info) == WEFM_OK) {
      j["stl_vertices"] = info.vertices;
      j["stl_merged_vertices"] = info.merged_vertices;
    }
  }
  wefm_mesh_release(mesh);
  // The tool's UV OBJ: one vt per vertex (a disk has one use per vertex), f v/vt.
  std::vector<double> uv_values(2 * static_cast<size_t>(f.vertices()));
  for (size_t v = 0; v < static_cast<size_t>(f.vertices()); ++v) {
    uv_values[2 * v] = f.xyz[3 * v] * 1.0000001;
    uv_values[2 * v + 1] = f.xyz[3 * v + 1] * 0.9999999;
  }
  wefm_cli::MeshDescription layout;
  layout.xyz = f.xyz;
  layout.elements = f.tri;
  layout.corner_uv = f.tri;
  layout.uv = uv_values;
  layout.groups = {{1, "face_1"}};
  timed("write_uv_obj", [&] {
    std::string error;
    if (wefm_cli::write_mesh(uv, wefm_cli::MeshFormat::obj, layout, error) != 0) status = "UV OBJ: " + error;
  });
  j["uv_obj_mb"] = file_mb(uv);
  j["status"] = status;
  for (const std::string& p : {obj, stl, uv}) std::remove(p.c_str());
  j["peak_rss_mb"] = peak_rss_mb();
  return j;
}

}  // namespace wefm_bench
