#include "case_runner.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>

#include "laplacian_floor.hpp"
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
struct StageClock {
  std::map<std::string, double> seconds;
  std::string current;
  double since = 0;
  static int callback(void* self, double, const char* stage) {
    auto* c = static_cast<StageClock*>(self);
    const double t = now_seconds();
    if (c->current != stage) {
      if (!c->current.empty()) c->seconds[c->current] += t - c->since;
      c->current = stage;
      c->since = t;
    }
    return 0;
  }
  void finish() {
    if (!current.empty() && current != "done") seconds[current] += now_seconds() - since;
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
  t = now_seconds();
  wefm_status st = wefm_face_set_mesh(face, f.vertices(), f.xyz.data(), f.triangles(), f.tri.data());
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
  Json stages = Json::object();
  for (const auto& [name, sec] : clock.seconds) stages[name] = sec;
  j["progress_stages"] = stages;
  wefm_face_release(face);
  j["peak_rss_mb"] = peak_rss_mb();
  return j;
}

Json run_floor_case(Shape shape, int64_t size, bool complex_arithmetic) {
  const Face f = generate(shape, size);
  Json j = face_header(complex_arithmetic ? "floor_complex" : "floor", shape, size, f);
  const double rss_before = current_rss_mb();
  const FloorResult r = measure_floor(f, complex_arithmetic);
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
  j["rss_before_mb"] = rss_before;
  j["peak_rss_mb"] = peak_rss_mb();
  return j;
}

Json run_read_case(Shape shape, int64_t size, const std::string& work_dir) {
  const Face f = generate(shape, size);
  Json j = face_header("read", shape, size, f);
  const std::string path = work_dir + "/" + shape_name(shape) + "_" + size_label(size) + ".obj";
  double t = now_seconds();
  if (!write_obj(path, f)) {
    j["status"] = path + ": " + std::strerror(errno);
    return j;
  }
  j["time_generator_write"] = now_seconds() - t;
  std::FILE* file = std::fopen(path.c_str(), "rb");
  if (file) {
    std::fseek(file, 0, SEEK_END);
    j["file_mb"] = static_cast<double>(std::ftell(file)) / (1024.0 * 1024.0);
    std::fclose(file);
  }
  t = now_seconds();
  wefm_mesh* mesh = nullptr;
  const wefm_status st = wefm_mesh_read(path.c_str(), 0.0, &mesh);
  j["time_read"] = now_seconds() - t;
  j["status"] = wefm_status_string(st);
  if (st != WEFM_OK) j["message"] = wefm_last_error();
  wefm_mesh_release(mesh);
  std::remove(path.c_str());
  j["peak_rss_mb"] = peak_rss_mb();
  return j;
}

}  // namespace wefm_bench
