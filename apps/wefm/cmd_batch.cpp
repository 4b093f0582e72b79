// wefm batch DIR|LISTFILE -o OUTDIR [-j N] [flatten options]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <thread>

#include "batch_inputs.hpp"
#include "batch_selection.hpp"
#include "command.hpp"
#include "exit_codes.hpp"
#include "face_job.hpp"
#include "face_threads.hpp"
#include "mesh_formats.hpp"
#include "output_file.hpp"
#include "output_paths.hpp"

namespace wefm_cli {

namespace {

std::vector<OptionSpec> batch_specs() {
  const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
  std::vector<OptionSpec> specs = {
      {"output", 'o', "OUTDIR", "directory for <name>.obj and <name>.json (created; required)", "", false},
      {"format", 0, mesh_format_names(), "format of the UV meshes OUTDIR/<name>.EXT", "obj", false},
      {"jobs", 'j', "N", "faces flattened at the same time, one thread each", std::to_string(hw), false},
      {"use-topology", 0, "", "in face folders, use topo.json instead of face.seam", "", false},
      {"summary-json", 0, "FILE", "also write the summary table as JSON", "", false},
      {"quiet", 'q', "", "no per-face progress lines (the summary table is still printed)", "", false},
      {"shard", 0, "I/N", "flatten only shard I of N (0-based I; every N-th face in name order)", "", false},
      {"skip-existing", 0, "", "skip a face whose outputs exist from an earlier run (reported as skipped)", "", false},
  };
  for (auto& s : solver_option_specs()) specs.push_back(s);
  return specs;
}

void print_help() {
  std::printf(
      "Usage: wefm batch DIR|LISTFILE -o OUTDIR [-j N] [options]\n\n"
      "Flattens many faces in parallel and writes OUTDIR/<name>.obj and OUTDIR/<name>.json (report).\n"
      "DIR: every .obj/.off/.stl/.ply in it (with <stem>.seam beside it when that has data) and every\n"
      "sub-folder holding face.obj (uses its face.seam when it has data, or topo.json with\n"
      "--use-topology), as in data/real. LISTFILE: one mesh file or face folder per line, # comments.\n"
      "One failing face is reported and the others go on. The exit code is 0 when every face succeeded,\n"
      "else the largest code of any face (6 if cancelled).\n"
      "Many machines: --shard I/N in each task of a job array (Slurm: --array=0-(N-1), --shard\n"
      "$SLURM_ARRAY_TASK_ID/N); --skip-existing resumes a stopped run (docs/SCALE-OUT.md).\n\nOptions:\n%s\n%s",
      format_options(batch_specs()).c_str(), exit_codes_help());
}

const char* status_text(const FaceOutcome& o, bool started) {
  if (!started) return "not started";
  switch (o.exit_code) {
    case kExitOk: return "ok";
    case kExitIo: return "io error";
    case kExitInvalid: return "invalid";
    case kExitSolver: return o.snap.has_result ? "not converged" : "solver failed";
    case kExitCancelled: return "cancelled";
    case kExitTimeLimit: return "time limit";
    default: return "failed";
  }
}

std::string fmt(const char* format, double v) {
  if (!std::isfinite(v)) return "-";
  char buf[32];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

struct BatchRequest {
  FlattenSettings settings;
  std::string source, ext, shard, summary_path;
  std::filesystem::path outdir;
  long long jobs = 1;
  bool use_topology = false, has_shard = false, has_summary = false, quiet = false, skip_existing = false;
};

// Parses and checks the arguments. Returns -1 to go on, else the exit code (help printed, bad usage).
int parse_request(const std::vector<std::string>& argv, BatchRequest& q) {
  const auto specs = batch_specs();
  ParsedArgs args;
  std::string error;
  auto usage = [](const std::string& message) {
    std::fprintf(stderr, "wefm batch: %s\n", message.c_str());
    return kExitUsage;
  };
  if (!parse_args(argv, specs, args, error) || (!args.help && !apply_solver_options(args, q.settings, error)))
    return usage(error + " (see wefm batch --help)");
  if (args.help) {
    print_help();
    return kExitOk;
  }
  if (args.positionals.size() != 1 || !args.has("output"))
    return usage("expected one DIR or LISTFILE and -o OUTDIR (see wefm batch --help)");
  q.jobs = std::max(1u, std::thread::hardware_concurrency());
  if (args.has("jobs") && (!parse_int(args.value("jobs"), q.jobs) || q.jobs < 1 || q.jobs > 1024))
    return usage("-j: expected a thread count >= 1, got '" + args.value("jobs") + "'");
  q.quiet = args.has("quiet");
  MeshFormat format = MeshFormat::obj;
  if (args.has("format") && !parse_mesh_format(args.value("format"), format, error)) return usage("--format: " + error);
  q.ext = mesh_format_extension(format);
  q.source = args.positionals[0];
  q.use_topology = args.has("use-topology");
  q.has_shard = args.has("shard");
  if (q.has_shard) q.shard = args.value("shard");
  q.outdir = args.value("output");
  q.has_summary = args.has("summary-json");
  if (q.has_summary) q.summary_path = args.value("summary-json");
  q.skip_existing = args.has("skip-existing");
  return -1;
}

// The faces this run flattens and where each one's outputs go (mesh, report).
struct BatchPlan {
  std::vector<BatchItem> items;
  std::vector<std::vector<std::string>> outputs;  // per item: the UV mesh, the report
};

// Finds the faces, keeps the shard's, checks the paths and makes OUTDIR. Returns -1 to go on, else
// the exit code.
int plan_batch(const BatchRequest& q, BatchPlan& plan) {
  std::string error;
  if (!find_batch_items(q.source, q.use_topology, plan.items, error)) {
    std::fprintf(stderr, "wefm: %s\n", error.c_str());
    return kExitIo;
  }
  if (q.has_shard) {
    Shard shard;
    if (!parse_shard(q.shard, shard, error)) {
      std::fprintf(stderr, "wefm batch: %s\n", error.c_str());
      return kExitUsage;
    }
    keep_shard(plan.items, shard);
  }
  if (q.outdir.empty()) {
    std::fprintf(stderr, "wefm batch: -o: empty directory name\n");
    return kExitUsage;
  }
  std::vector<NamedPath> inputs, outputs;
  for (const BatchItem& item : plan.items) {
    inputs.push_back({"input", item.input});
    inputs.push_back({"seams of " + item.name, item.seams});
    inputs.push_back({"topology of " + item.name, item.topology});
    outputs.push_back({"output of " + item.name, (q.outdir / (item.name + q.ext)).string()});
    outputs.push_back({"report of " + item.name, (q.outdir / (item.name + ".json")).string()});
    plan.outputs.push_back({outputs[outputs.size() - 2].path, outputs.back().path});
  }
  if (q.has_summary) outputs.push_back({"--summary-json", q.summary_path});
  if (!check_output_paths(inputs, outputs, error)) {
    std::fprintf(stderr, "wefm batch: %s\n", error.c_str());
    return kExitUsage;
  }
  if (!make_dirs(q.outdir.string(), error)) {
    std::fprintf(stderr, "wefm: %s\n", error.c_str());
    return kExitIo;
  }
  return -1;
}

// What each face gave.
struct BatchRuns {
  std::vector<FaceOutcome> results;
  std::vector<char> started;
  // Faces done by an earlier run keep their outputs; the summary shows what those reports say.
  std::vector<char> skipped;
  std::vector<int> codes;  // exit code per face; a face not started has the stop's
};

const char* status_of(const BatchRuns& runs, size_t i) {
  return runs.skipped[i] ? "skipped" : status_text(runs.results[i], runs.started[i]);
}

// Flattens the faces on up to -j threads, one face job each (a skipped face is only counted).
BatchRuns flatten_all_faces(const BatchRequest& q, const BatchPlan& plan) {
  const std::vector<BatchItem>& items = plan.items;
  BatchRuns runs;
  runs.results.resize(items.size());
  runs.started.assign(items.size(), 0);
  runs.skipped.assign(items.size(), 0);
  if (q.skip_existing)
    for (size_t i = 0; i < items.size(); ++i)
      runs.skipped[i] = earlier_result(plan.outputs[i], plan.outputs[i].back(), runs.results[i]);
  CancelWatcher watcher;
  auto work = [&](size_t i) {
    runs.started[i] = 1;
    if (runs.skipped[i]) return true;
    const BatchItem& item = items[i];
    FaceJob job;
    job.input = item.input;
    job.output_mesh = plan.outputs[i][0];
    job.settings = q.settings;
    job.settings.seams_path = item.seams;
    job.settings.topology_path = item.topology;
    job.settings.report_path = plan.outputs[i][1];
    job.watcher = &watcher;
    runs.results[i] = run_face_job(job);
    return true;
  };
  auto finished = [&](size_t i, size_t done) {
    if (q.quiet) return;
    if (runs.skipped[i]) {
      std::fprintf(stderr, "[%zu/%zu] %s: skipped (outputs exist)\n", done, items.size(), items[i].name.c_str());
      return;
    }
    const FaceOutcome& o = runs.results[i];
    std::fprintf(stderr, "[%zu/%zu] %s: %s (%.2f s)%s%s\n", done, items.size(), items[i].name.c_str(), status_text(o, true),
                 o.time.total, o.error.empty() ? "" : ": ", o.error.c_str());
  };
  for_each_face(items.size(), static_cast<size_t>(q.jobs), work, finished);
  for (size_t i = 0; i < items.size(); ++i) runs.codes.push_back(runs.started[i] ? runs.results[i].exit_code : stop_exit_code());
  return runs;
}

// The table, the batch line and the failures on stderr. Returns the worst face's exit code.
int print_results(const BatchRequest& q, const std::vector<BatchItem>& items, const BatchRuns& runs) {
  size_t width = 4;
  for (const auto& it : items) width = std::max(width, it.name.size());
  std::printf("%-*s %9s %9s %6s %8s %8s  %s\n", static_cast<int>(width), "name", "tris", "score", "flips", "overlaps",
              "time", "status");
  int exit_code = kExitOk;
  size_t ok = 0, partial = 0;  // partial: not converged but written
  for (size_t i = 0; i < items.size(); ++i) {
    const FaceOutcome& o = runs.results[i];
    const bool has = o.snap.has_result;
    const wefm_report& r = o.snap.report;
    std::printf("%-*s %9lld %9s %6s %8s %7.2fs  %s\n", static_cast<int>(width), items[i].name.c_str(),
                static_cast<long long>(o.snap.info.triangles), has ? fmt("%.4f", r.score).c_str() : "-",
                has ? std::to_string(r.flipped_triangles).c_str() : "-",
                has ? std::to_string(r.boundary_intersections).c_str() : "-", o.time.total, status_of(runs, i));
    if (runs.codes[i] == kExitOk) ++ok;
    exit_code = std::max(exit_code, runs.codes[i]);
    partial += runs.started[i] && o.exit_code == kExitSolver && has;
  }
  const size_t n_skipped = static_cast<size_t>(std::count(runs.skipped.begin(), runs.skipped.end(), 1));
  std::printf("%zu faces: %zu ok, %zu not converged (written), %zu failed", items.size(), ok, partial,
              items.size() - ok - partial);
  if (q.skip_existing) std::printf(" (%zu skipped: outputs exist)", n_skipped);
  std::printf("; outputs in %s\n", q.outdir.string().c_str());
  for (size_t i = 0; i < items.size(); ++i)
    if (runs.results[i].exit_code != kExitOk && !runs.skipped[i])
      std::fprintf(stderr, "wefm: %s: %s\n", items[i].name.c_str(), runs.results[i].error.c_str());
  return exit_code;
}

// The table as JSON, one row per face (--summary-json).
nlohmann::ordered_json summary_json(const std::vector<BatchItem>& items, const BatchRuns& runs) {
  using Json = nlohmann::ordered_json;
  Json rows = Json::array();
  for (size_t i = 0; i < items.size(); ++i) {
    const FaceOutcome& o = runs.results[i];
    const bool has = o.snap.has_result;
    const wefm_report& r = o.snap.report;
    Json row;
    row["name"] = items[i].name;
    row["input"] = items[i].input;
    row["triangles"] = o.snap.info.triangles;
    row["score"] = has && std::isfinite(r.score) ? Json(r.score) : Json(nullptr);
    row["flipped_triangles"] = has ? Json(r.flipped_triangles) : Json(nullptr);
    row["boundary_intersections"] = has ? Json(r.boundary_intersections) : Json(nullptr);
    row["time"] = o.time.total;
    row["status"] = status_of(runs, i);
    row["exit_code"] = runs.codes[i];
    row["message"] = o.error;
    rows.push_back(std::move(row));
  }
  return rows;
}

int run_batch(const std::vector<std::string>& argv) {
  BatchRequest q;
  if (const int code = parse_request(argv, q); code >= 0) return code;
  BatchPlan plan;
  if (const int code = plan_batch(q, plan); code >= 0) return code;
  const BatchRuns runs = flatten_all_faces(q, plan);
  int exit_code = print_results(q, plan.items, runs);
  if (q.has_summary) {
    std::string error;
    if (const int code = write_file_atomically(q.summary_path, summary_json(plan.items, runs).dump(2) + '\n', error)) {
      std::fprintf(stderr, "wefm: %s\n", error.c_str());
      exit_code = std::max<int>(exit_code, code);
    }
  }
  return exit_after_stop(exit_code, "batch");
}

}  // namespace

Command batch_command() { return {"batch", "flatten many faces in parallel (directory or list file)", run_batch}; }

}  // namespace wefm_cli
