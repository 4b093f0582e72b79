// wefm model MODEL.step -o OUTDIR [-j N] [--deflection D] [flatten options]
//
// Imports a CAD model (apps/cad, Open CASCADE), writes every face as input files (OBJ + topo.json:
// the face's own reproducer; OBJ whatever --format, as `wefm flatten` reads it) and flattens them in parallel with the same per-face pipeline as
// `wefm flatten --topology` (face_job), one handle per thread. A face that fails to import or to
// flatten is reported with its reason; the others carry on.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <thread>

#include "command.hpp"
#include "exit_codes.hpp"

#ifdef WEFM_CLI_HAVE_OCCT
#include "cad_plugin_loader.hpp"
#include "cad_face_files.hpp"
#include "cad_model.hpp"
#include "face_job.hpp"
#include "face_threads.hpp"
#include "mesh_formats.hpp"
#include "model_atlas.hpp"
#include "names.hpp"
#include "output_file.hpp"
#include "output_paths.hpp"
#endif

namespace wefm_cli {

namespace {

#ifdef WEFM_CLI_HAVE_OCCT

using Json = nlohmann::ordered_json;

std::vector<OptionSpec> model_specs() {
  const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
  const wefm_cad::TessellationSettings d;
  char defl[32], ang[32];
  std::snprintf(defl, sizeof defl, "%g", d.relative_deflection);
  std::snprintf(ang, sizeof ang, "%g", d.angular_deflection);
  std::vector<OptionSpec> specs = {
      {"output", 'o', "OUTDIR", "directory for the per-face files and index.json (created; required)", "", false},
      {"jobs", 'j', "N", "faces flattened at the same time, one thread and one handle each", std::to_string(hw), false},
      {"deflection", 0, "D", "BRepMesh linear deflection as a fraction of the bounding-box diagonal", defl, false},
      {"angular-deflection", 0, "RAD", "BRepMesh angular deflection in radians", ang, false},
      {"keep-triangulation", 0, "", "keep a triangulation the file carries (BREP); mesh only faces without one", "",
       false},
      {"face", 0, "N", "flatten only face N (1-based, as in the index)", "", true},
      {"atlas", 0, "FILE.svg", "write an SVG atlas of all domains", "", false},
      {"format", 0, mesh_format_names(), "format of the per-face UV meshes OUTDIR/fNNN.EXT (the input faces stay OBJ)", "obj", false},
      {"quiet", 'q', "", "no per-face progress lines (the summary table is still printed)", "", false},
  };
  for (auto& s : solver_option_specs())
    if (s.name != "edge-mode-of") specs.push_back(s);  // edge ids differ per face: not meaningful here
  return specs;
}

void print_help() {
  std::printf(
      "Usage: wefm model MODEL.step|.stp|.iges|.igs|.brep -o OUTDIR [-j N] [--deflection D] [options]\n\n"
      "Imports a CAD model with Open CASCADE, tessellates every face (BRepMesh) and flattens all faces in\n"
      "parallel. Seam edges become repeated edges and model edges keep their ids across faces. Writes per\n"
      "face OUTDIR/input/fNNN.obj + fNNN.topo.json (the face as imported: `wefm flatten fNNN.obj --topology\n"
      "fNNN.topo.json` reproduces it), OUTDIR/fNNN.obj (domain, UVs; --format msh|vtk|vtu|ply for another\n"
      "format, the face as physical group \"face_N\" or face_id N) and OUTDIR/fNNN.json (report), and\n"
      "OUTDIR/index.json for the model. Prints a summary by surface type. One failing face is reported\n"
      "and the others go on; the exit code is 0 when every face succeeded, else the largest code of any face.\n\n"
      "Options:\n%s\n%s",
      format_options(model_specs()).c_str(), exit_codes_help());
}

std::string face_name(int index) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "f%03d", index);
  return buf;
}

Json number(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

// The face as imported, the input of its flatten: OBJ, numbers that read back bit for bit.
int write_face_input(const std::string& path, const wefm_cad::CadFace& f, const std::string& model_path, std::string& error) {
  MeshDescription d;
  d.comments = {"face " + std::to_string(f.index) + " (" + f.surface_type + ") of " + model_path};
  d.xyz = f.xyz;
  d.elements = f.triangles;
  d.digits17 = true;
  return write_mesh(path, MeshFormat::obj, d, error);
}

struct FaceRun {
  const wefm_cad::CadFace* face = nullptr;
  std::string name, input_obj, input_topo, domain_obj, report;
  bool started = false;
  int exit_code = kExitOk;
  std::string reason;     // import or flatten failure
  FaceOutcome outcome;
};

const char* status_of(const FaceRun& r) {
  if (!r.started) return is_stop_code(r.exit_code) ? "skipped" : "failed";
  if (r.exit_code == kExitOk) return "ok";
  if (r.exit_code == kExitSolver && r.outcome.snap.has_result) return "not_converged";
  return r.exit_code == kExitCancelled ? "cancelled" : r.exit_code == kExitTimeLimit ? "time_limit" : "failed";
}

Json face_entry(const FaceRun& r, const std::filesystem::path& outdir) {
  const wefm_cad::CadFace& f = *r.face;
  const FaceSnapshot& s = r.outcome.snap;
  const bool has = r.started && s.has_result;
  const wefm_report& rep = s.report;
  auto rel = [&](const std::string& p) { return std::filesystem::relative(p, outdir).string(); };
  Json j;
  j["face"] = f.index;
  j["name"] = r.name;
  j["surface_type"] = f.surface_type;
  j["status"] = status_of(r);
  j["exit_code"] = r.exit_code;
  j["reason"] = r.reason;
  j["vertices"] = f.xyz.size() / 3;
  j["triangles"] = f.triangles.size() / 3;
  j["dropped_triangles"] = f.dropped_triangles;
  j["triangulation_kept"] = f.triangulation_kept;
  size_t seams = 0, degenerate = 0;
  for (const auto& e : f.edges) {
    seams += e.seam;
    degenerate += e.degenerated;
  }
  j["edges"] = f.edges.size();
  j["loops"] = f.loops.size();
  j["seam_edges"] = seams;
  j["degenerate_edges"] = degenerate;
  Json decisions = Json::array();
  if (has)
    for (const EdgeDecision& d : s.decisions) {
      Json scores;
      for (int m = WEFM_EDGE_FREE; m <= WEFM_EDGE_ROTATIONAL; ++m) scores[edge_mode_name(m)] = number(d.scores[static_cast<size_t>(m)]);
      decisions.push_back({{"edge_id", d.id}, {"mode", edge_mode_name(d.mode)}, {"requested", edge_mode_name(d.requested)},
                           {"scores", scores}});
    }
  j["seam_decisions"] = decisions;
  j["score"] = has ? number(rep.score) : Json(nullptr);
  j["flipped_triangles"] = has ? Json(rep.flipped_triangles) : Json(nullptr);
  j["boundary_intersections"] = has ? Json(rep.boundary_intersections) : Json(nullptr);
  j["area_distortion_mean"] = has ? number(rep.area_distortion_mean) : Json(nullptr);
  j["area_distortion_max"] = has ? number(rep.area_distortion_max) : Json(nullptr);
  j["angle_distortion_mean"] = has ? number(rep.angle_distortion_mean) : Json(nullptr);
  j["angle_distortion_max"] = has ? number(rep.angle_distortion_max) : Json(nullptr);
  j["s"] = has ? number(rep.s) : Json(nullptr);
  j["time"] = r.started ? Json(r.outcome.time.total) : Json(nullptr);
  Json files;
  if (!r.input_obj.empty()) {
    files["input_obj"] = rel(r.input_obj);
    files["input_topology"] = rel(r.input_topo);
  }
  for (const auto& [what, path] : r.outcome.outputs) files[what == "uv mesh" ? "domain_obj" : what] = rel(path);
  j["files"] = files;
  return j;
}

struct TypeRow {
  int faces = 0, ok = 0, not_converged = 0, failed = 0, flipped_faces = 0, intersecting_faces = 0;
  int64_t flips = 0, intersections = 0;
  double score_sum = 0;
  int scored = 0;
  double time = 0;
};

void add_to_row(TypeRow& row, const FaceRun& r) {
  ++row.faces;
  const std::string st = status_of(r);
  if (st == "ok") ++row.ok;
  else if (st == "not_converged") ++row.not_converged;
  else ++row.failed;
  row.time += r.started ? r.outcome.time.total : 0;
  const FaceSnapshot& s = r.outcome.snap;
  if (!r.started || !s.has_result) return;
  row.flips += s.report.flipped_triangles;
  row.flipped_faces += s.report.flipped_triangles > 0;
  row.intersections += s.report.boundary_intersections;
  row.intersecting_faces += s.report.boundary_intersections > 0;
  if (std::isfinite(s.report.score)) {
    row.score_sum += s.report.score;
    ++row.scored;
  }
}

void print_row(const char* name, const TypeRow& r) {
  char score[16] = "-";
  if (r.scored) std::snprintf(score, sizeof score, "%.4f", r.score_sum / r.scored);
  std::printf("%-12s %6d %5d %8d %7d %11d %8lld %10d %9s %8.2fs\n", name, r.faces, r.ok, r.not_converged, r.failed,
              r.flipped_faces, static_cast<long long>(r.flips), r.intersecting_faces, score, r.time);
}

struct ModelRequest {
  FlattenSettings settings;
  std::string model_path, atlas_path;  // atlas_path empty: no atlas
  std::filesystem::path outdir;
  long long jobs = 1;
  wefm_cad::TessellationSettings tess;
  std::set<long long> only;  // face numbers; empty: every face
  MeshFormat format = MeshFormat::obj;
  bool quiet = false;
};

// Parses and checks the arguments. Returns -1 to go on, else the exit code (help printed, bad usage).
int parse_request(const std::vector<std::string>& argv, ModelRequest& q) {
  const auto specs = model_specs();
  ParsedArgs args;
  std::string error;
  auto usage = [](const std::string& message) {
    std::fprintf(stderr, "wefm model: %s\n", message.c_str());
    return kExitUsage;
  };
  if (!parse_args(argv, specs, args, error) || (!args.help && !apply_solver_options(args, q.settings, error)))
    return usage(error + " (see wefm model --help)");
  if (args.help) {
    print_help();
    return kExitOk;
  }
  if (args.positionals.size() != 1 || !args.has("output"))
    return usage("expected one MODEL file and -o OUTDIR (see wefm model --help)");
  q.jobs = std::max(1u, std::thread::hardware_concurrency());
  if (args.has("jobs") && (!parse_int(args.value("jobs"), q.jobs) || q.jobs < 1 || q.jobs > 1024))
    return usage("-j: expected a thread count >= 1, got '" + args.value("jobs") + "'");
  for (auto [name, field] : {std::pair<const char*, double*>{"deflection", &q.tess.relative_deflection},
                             std::pair<const char*, double*>{"angular-deflection", &q.tess.angular_deflection}})
    if (args.has(name) && (!parse_double(args.value(name), *field) || !(*field > 0)))
      return usage(std::string("--") + name + ": expected a number > 0, got '" + args.value(name) + "'");
  q.tess.keep_triangulation = args.has("keep-triangulation");
  if (args.has("face"))
    for (const std::string& v : args.values.at("face")) {
      long long k = 0;
      if (!parse_int(v, k) || k < 1) return usage("--face: expected a face number >= 1, got '" + v + "'");
      q.only.insert(k);
    }
  q.quiet = args.has("quiet");
  if (args.has("format") && !parse_mesh_format(args.value("format"), q.format, error)) return usage("--format: " + error);
  q.model_path = args.positionals[0];
  q.outdir = args.value("output");
  if (args.has("atlas")) q.atlas_path = args.value("atlas");
  // The per-face files (.obj, .json) cannot be the model (.step, .iges, .brep); index.json and the
  // atlas are checked here, before the import.
  std::vector<NamedPath> outputs = {{"-o", args.value("output")}};
  if (!q.outdir.empty()) outputs = {{"the index", (q.outdir / "index.json").string()}};
  if (args.has("atlas")) outputs.push_back({"--atlas", q.atlas_path});
  if (!check_output_paths({{"MODEL", q.model_path}}, outputs, error)) return usage(error);
  return -1;
}

// Writes every face's input files (the ones --face selects) into OUTDIR/input and lists the runs; a
// face that failed to import gets its reason instead. Returns -1 to go on, else the exit code.
int write_face_inputs(const ModelRequest& q, const wefm_cad::CadModel& model, std::vector<FaceRun>& runs) {
  std::string error;
  if (!make_dirs((q.outdir / "input").string(), error)) {
    std::fprintf(stderr, "wefm: %s\n", error.c_str());
    return kExitIo;
  }
  for (const auto& f : model.faces) {
    if (!q.only.empty() && !q.only.count(f.index)) continue;
    FaceRun r;
    r.face = &f;
    r.name = face_name(f.index);
    if (!f.error.empty()) {
      r.exit_code = kExitInvalid;
      r.reason = "import: " + f.error;
    } else {
      r.input_obj = (q.outdir / "input" / (r.name + ".obj")).string();
      r.input_topo = (q.outdir / "input" / (r.name + ".topo.json")).string();
      int code = write_face_input(r.input_obj, f, q.model_path, error);
      if (code == kExitOk) code = write_file_atomically(r.input_topo, wefm_cad::face_topology_text(f, q.model_path), error);
      if (code != kExitOk) {
        std::fprintf(stderr, "wefm: %s\n", error.c_str());
        return code;
      }
      r.domain_obj = (q.outdir / (r.name + mesh_format_extension(q.format))).string();
      r.report = (q.outdir / (r.name + ".json")).string();
    }
    runs.push_back(std::move(r));
  }
  return -1;
}

// Flattens the imported faces on `n_threads` threads, one face job each; a face not started because
// of a stop request gets the stop's exit code. Returns the wall time, seconds.
double flatten_all_faces(const ModelRequest& q, std::vector<FaceRun>& runs, size_t n_threads) {
  CancelWatcher watcher;
  const auto t0 = std::chrono::steady_clock::now();
  auto work = [&](size_t i) {
    FaceRun& r = runs[i];
    if (r.input_obj.empty()) return false;  // import failed: nothing to flatten
    FaceJob job;
    job.input = r.input_obj;
    job.output_mesh = r.domain_obj;
    job.face_tag = r.face->index;
    job.settings = q.settings;
    job.settings.topology_path = r.input_topo;
    job.settings.report_path = r.report;
    job.watcher = &watcher;
    r.started = true;
    r.outcome = run_face_job(job);
    r.exit_code = r.outcome.exit_code;
    r.reason = r.outcome.error;
    return true;
  };
  auto finished = [&](size_t i, size_t done) {
    const FaceRun& r = runs[i];
    if (!q.quiet)
      std::fprintf(stderr, "[%zu/%zu] %s %s: %s (%.2f s)\n", done, runs.size(), r.name.c_str(), r.face->surface_type.c_str(),
                   status_of(r), r.outcome.time.total);
  };
  for_each_face(runs.size(), n_threads, work, finished);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  for (FaceRun& r : runs)
    if (!r.started && r.input_obj.size() && interrupted()) r.exit_code = stop_exit_code();
  return wall;
}

// The faces counted by surface type and over all.
struct ModelSummary {
  std::map<std::string, TypeRow> by_type;
  TypeRow total;
};

ModelSummary summarise(const std::vector<FaceRun>& runs) {
  ModelSummary sum;
  for (const FaceRun& r : runs) {
    add_to_row(sum.by_type[r.face->surface_type], r);
    add_to_row(sum.total, r);
  }
  return sum;
}

// The table by surface type, the model line and the failures on stderr. Returns the worst face's exit code.
int print_results(const ModelRequest& q, const std::vector<FaceRun>& runs, const ModelSummary& sum, double wall,
                  size_t n_threads) {
  std::printf("%-12s %6s %5s %8s %7s %11s %8s %10s %9s %9s\n", "surface", "faces", "ok", "not_conv", "failed",
              "flip_faces", "flips", "bnd_int", "mean_scr", "time");
  for (const auto& [type, row] : sum.by_type) print_row(type.c_str(), row);
  print_row("all", sum.total);
  std::printf("%s: %d faces, %d ok, %d not converged (written), %d failed; flatten wall time %.2f s with -j %zu; outputs in %s\n",
              q.model_path.c_str(), sum.total.faces, sum.total.ok, sum.total.not_converged, sum.total.failed, wall, n_threads,
              q.outdir.string().c_str());
  int exit_code = kExitOk;
  for (const FaceRun& r : runs) {
    exit_code = std::max(exit_code, r.exit_code);
    if (r.exit_code != kExitOk)
      std::fprintf(stderr, "wefm: %s face %d (%s, %zu triangles): %s\n", q.model_path.c_str(), r.face->index,
                   r.face->surface_type.c_str(), r.face->triangles.size() / 3, r.reason.c_str());
  }
  return exit_code;
}

Json index_json(const ModelRequest& q, const wefm_cad::CadModel& model, const std::vector<FaceRun>& runs,
                const ModelSummary& sum, double wall, size_t n_threads) {
  Json index;
  index["wefm_version"] = wefm_version();
  index["model"] = q.model_path;
  index["format"] = model.format;
  index["faces_in_model"] = model.faces.size();
  index["edges_in_model"] = model.edge_count;
  index["bbox_diagonal"] = model.bbox_diagonal;
  index["tessellation"] = {{"relative_deflection", q.tess.relative_deflection},
                           {"linear_deflection", model.linear_deflection},
                           {"angular_deflection", q.tess.angular_deflection},
                           {"keep_triangulation", q.tess.keep_triangulation}};
  index["timings"] = {{"read", model.time_read}, {"mesh", model.time_mesh}, {"import", model.time_extract},
                      {"flatten_wall", wall}, {"jobs", n_threads}};
  Json summary = Json::object();
  for (const auto& [type, row] : sum.by_type)
    summary[type] = {{"faces", row.faces}, {"ok", row.ok}, {"not_converged", row.not_converged}, {"failed", row.failed},
                     {"flipped_faces", row.flipped_faces}, {"flipped_triangles", row.flips},
                     {"intersecting_faces", row.intersecting_faces}, {"boundary_intersections", row.intersections},
                     {"mean_score", row.scored ? Json(row.score_sum / row.scored) : Json(nullptr)}};
  index["summary"] = summary;
  Json faces = Json::array();
  for (const FaceRun& r : runs) faces.push_back(face_entry(r, q.outdir));
  index["faces"] = faces;
  return index;
}

// One cell per face: its domain with the score, or its status and reason.
int write_atlas(const ModelRequest& q, const std::vector<FaceRun>& runs, std::string& error) {
  std::vector<AtlasCell> cells;
  for (const FaceRun& r : runs) {
    AtlasCell c;
    c.title = r.name + " " + r.face->surface_type + " (" + std::to_string(r.face->triangles.size() / 3) + " tris)";
    c.snap = r.started ? &r.outcome.snap : nullptr;
    char buf[96];
    if (c.snap && c.snap->has_result)
      std::snprintf(buf, sizeof buf, "score %.4f, %lld flips, %lld bnd int%s", c.snap->report.score,
                    static_cast<long long>(c.snap->report.flipped_triangles),
                    static_cast<long long>(c.snap->report.boundary_intersections),
                    r.exit_code == kExitOk ? "" : " (not converged)");
    c.caption = c.snap && c.snap->has_result ? std::string(buf) : std::string(status_of(r)) + ": " + r.reason;
    cells.push_back(std::move(c));
  }
  if (!make_parent_dirs(q.atlas_path, error)) return kExitIo;
  const std::string title = std::filesystem::path(q.model_path).filename().string() + ": UV domains";
  return write_model_atlas(q.atlas_path, title, cells, error) != kExitOk ? kExitIo : kExitOk;
}

int run_model(const std::vector<std::string>& argv) {
  ModelRequest q;
  if (const int code = parse_request(argv, q); code >= 0) return code;
  std::string error;
  wefm_cad::CadModel model;
  if (const int code = load_cad_model_via_plugin(q.model_path, q.tess, model, error)) {
    std::fprintf(stderr, "wefm: %s\n", error.c_str());
    return code;
  }
  std::vector<FaceRun> runs;
  if (const int code = write_face_inputs(q, model, runs); code >= 0) return code;
  if (!q.quiet)
    std::fprintf(stderr, "%s: %zu faces, %lld edges; read %.2f s, BRepMesh %.2f s (deflection %g), import %.2f s\n",
                 q.model_path.c_str(), model.faces.size(), static_cast<long long>(model.edge_count), model.time_read,
                 model.time_mesh, model.linear_deflection, model.time_extract);
  const size_t n_threads = std::min<size_t>(static_cast<size_t>(q.jobs), std::max<size_t>(1, runs.size()));
  const double wall = flatten_all_faces(q, runs, n_threads);

  const ModelSummary sum = summarise(runs);
  int exit_code = print_results(q, runs, sum, wall, n_threads);
  const Json index = index_json(q, model, runs, sum, wall, n_threads);
  if (const int code = write_file_atomically((q.outdir / "index.json").string(), index.dump(1) + '\n', error)) {
    std::fprintf(stderr, "wefm: %s\n", error.c_str());
    exit_code = std::max<int>(exit_code, code);
  }
  if (!q.atlas_path.empty()) {
    if (const int code = write_atlas(q, runs, error)) {
      std::fprintf(stderr, "wefm: %s\n", error.c_str());
      exit_code = std::max<int>(exit_code, code);
    }
  }
  return exit_after_stop(exit_code, q.model_path);
}

#else  // built without Open CASCADE

int run_model(const std::vector<std::string>&) {
  std::fprintf(stderr,
               "wefm model: this wefm was built without CAD import (WEFM_WITH_OCCT=OFF; install Debian's "
               "libocct-*-dev packages, scripts/install-deps.sh, and reconfigure)\n");
  return kExitIo;
}

#endif

}  // namespace

Command model_command() { return {"model", "import a CAD model (STEP, IGES, BREP) and flatten every face", run_model}; }

}  // namespace wefm_cli
