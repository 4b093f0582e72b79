// wefm batch DIR|LISTFILE -o OUTDIR [-j N] [flatten options]
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <mutex>
#include <nlohmann/json.hpp>
#include <thread>

#include "batch_inputs.hpp"
#include "batch_selection.hpp"
#include "command.hpp"
#include "exit_codes.hpp"
#include "face_job.hpp"
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

int run_batch(const std::vector<std::string>& argv) {
  const auto specs = batch_specs();
  ParsedArgs args;
  std::string error;
  FlattenSettings settings;
  if (!parse_args(argv, specs, args, error) || (!args.help && !apply_solver_options(args, settings, error))) {
    std::fprintf(stderr, "wefm batch: %s (see wefm batch --help)\n", error.c_str());
    return kExitUsage;
  }
  if (args.help) {
    print_help();
    return kExitOk;
  }
  if (args.positionals.size() != 1 || !args.has("output")) {
    std::fprintf(stderr, "wefm batch: expected one DIR or LISTFILE and -o OUTDIR (see wefm batch --help)\n");
    return kExitUsage;
  }
  long long jobs = std::max(1u, std::thread::hardware_concurrency());
  if (args.has("jobs") && (!parse_int(args.value("jobs"), jobs) || jobs < 1 || jobs > 1024)) {
    std::fprintf(stderr, "wefm batch: -j: expected a thread count >= 1, got '%s'\n", args.value("jobs").c_str());
    return kExitUsage;
  }
  const bool quiet = args.has("quiet");
  MeshFormat format = MeshFormat::obj;
  if (args.has("format") && !parse_mesh_format(args.value("format"), format, error)) {
    std::fprintf(stderr, "wefm batch: --format: %s\n", error.c_str());
    return kExitUsage;
  }
  const std::string ext = mesh_format_extension(format);
  std::vector<BatchItem> items;
  if (!find_batch_items(args.positionals[0], args.has("use-topology"), items, error)) {
    std::fprintf(stderr, "wefm: %s\n", error.c_str());
    return kExitIo;
  }
  if (args.has("shard")) {
    Shard shard;
    if (!parse_shard(args.value("shard"), shard, error)) {
      std::fprintf(stderr, "wefm batch: %s\n", error.c_str());
      return kExitUsage;
    }
    keep_shard(items, shard);
  }
  const std::filesystem::path outdir = args.value("output");
  if (outdir.empty()) {
    std::fprintf(stderr, "wefm batch: -o: empty directory name\n");
    return kExitUsage;
  }
  std::vector<NamedPath> inputs, outputs;
  std::vector<std::vector<std::string>> item_outputs;  // what --skip-existing looks for
  for (const BatchItem& item : items) {
    inputs.push_back({"input", item.input});
    inputs.push_back({"seams of " + item.name, item.seams});
    inputs.push_back({"topology of " + item.name, item.topology});
    outputs.push_back({"output of " + item.name, (outdir / (item.name + ext)).string()});
    outputs.push_back({"report of " + item.name, (outdir / (item.name + ".json")).string()});
    item_outputs.push_back({outputs[outputs.size() - 2].path, outputs.back().path});
  }
  if (args.has("summary-json")) outputs.push_back({"--summary-json", args.value("summary-json")});
  if (!check_output_paths(inputs, outputs, error)) {
    std::fprintf(stderr, "wefm batch: %s\n", error.c_str());
    return kExitUsage;
  }
  if (!make_dirs(outdir.string(), error)) {
    std::fprintf(stderr, "wefm: %s\n", error.c_str());
    return kExitIo;
  }

  CancelWatcher watcher;
  std::vector<FaceOutcome> results(items.size());
  std::vector<char> started(items.size(), 0);
  // Faces done by an earlier run keep their outputs; the summary shows what those reports say.
  std::vector<char> skipped(items.size(), 0);
  if (args.has("skip-existing"))
    for (size_t i = 0; i < items.size(); ++i)
      skipped[i] = earlier_result(item_outputs[i], item_outputs[i].back(), results[i]);
  std::atomic<size_t> next{0};
  std::atomic<size_t> finished{0};
  std::mutex print_mutex;
  auto worker = [&] {
    for (size_t i; !interrupted() && (i = next++) < items.size();) {
      const BatchItem& item = items[i];
      if (skipped[i]) {
        started[i] = 1;
        const size_t done = ++finished;
        if (!quiet) {
          std::lock_guard<std::mutex> lock(print_mutex);
          std::fprintf(stderr, "[%zu/%zu] %s: skipped (outputs exist)\n", done, items.size(), item.name.c_str());
        }
        continue;
      }
      FaceJob job;
      job.input = item.input;
      job.output_mesh = (outdir / (item.name + ext)).string();
      job.settings = settings;
      job.settings.seams_path = item.seams;
      job.settings.topology_path = item.topology;
      job.settings.report_path = (outdir / (item.name + ".json")).string();
      job.watcher = &watcher;
      started[i] = 1;
      results[i] = run_face_job(job);
      const size_t done = ++finished;
      if (!quiet) {
        std::lock_guard<std::mutex> lock(print_mutex);
        const FaceOutcome& o = results[i];
        std::fprintf(stderr, "[%zu/%zu] %s: %s (%.2f s)%s%s\n", done, items.size(), item.name.c_str(),
                     status_text(o, true), o.time.total, o.error.empty() ? "" : ": ", o.error.c_str());
      }
    }
  };
  std::vector<std::thread> threads;
  const size_t n_threads = std::min<size_t>(static_cast<size_t>(jobs), items.size());
  for (size_t t = 0; t < n_threads; ++t) threads.emplace_back(worker);
  for (auto& t : threads) t.join();

  // Summary table.
  size_t width = 4;
  for (const auto& it : items) width = std::max(width, it.name.size());
  std::printf("%-*s %9s %9s %6s %8s %8s  %s\n", static_cast<int>(width), "name", "tris", "score", "flips", "overlaps",
              "time", "status");
  int exit_code = kExitOk;
  size_t ok = 0;
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (size_t i = 0; i < items.size(); ++i) {
    const FaceOutcome& o = results[i];
    const bool has = o.snap.has_result;
    const wefm_report& r = o.snap.report;
    std::printf("%-*s %9lld %9s %6s %8s %7.2fs  %s\n", static_cast<int>(width), items[i].name.c_str(),
                static_cast<long long>(o.snap.info.triangles), has ? fmt("%.4f", r.score).c_str() : "-",
                has ? std::to_string(r.flipped_triangles).c_str() : "-",
                has ? std::to_string(r.boundary_intersections).c_str() : "-", o.time.total,
                skipped[i] ? "skipped" : status_text(o, started[i]));
    const int code = started[i] ? o.exit_code : stop_exit_code();
    if (code == kExitOk) ++ok;
    exit_code = std::max(exit_code, code);
    nlohmann::ordered_json row;
    row["name"] = items[i].name;
    row["input"] = items[i].input;
    row["triangles"] = o.snap.info.triangles;
    row["score"] = has && std::isfinite(r.score) ? nlohmann::ordered_json(r.score) : nlohmann::ordered_json(nullptr);
    row["flipped_triangles"] = has ? nlohmann::ordered_json(r.flipped_triangles) : nlohmann::ordered_json(nullptr);
    row["boundary_intersections"] = has ? nlohmann::ordered_json(r.boundary_intersections) : nlohmann::ordered_json(nullptr);
    row["time"] = o.time.total;
    row["status"] = skipped[i] ? "skipped" : status_text(o, started[i]);
    row["exit_code"] = code;
    row["message"] = o.error;
    rows.push_back(std::move(row));
  }
  size_t partial = 0;  // not converged but written
  for (size_t i = 0; i < items.size(); ++i) partial += started[i] && results[i].exit_code == kExitSolver && results[i].snap.has_result;
  const size_t n_skipped = static_cast<size_t>(std::count(skipped.begin(), skipped.end(), 1));
  std::printf("%zu faces: %zu ok, %zu not converged (written), %zu failed", items.size(), ok, partial,
              items.size() - ok - partial);
  if (args.has("skip-existing")) std::printf(" (%zu skipped: outputs exist)", n_skipped);
  std::printf("; outputs in %s\n", outdir.string().c_str());
  for (size_t i = 0; i < items.size(); ++i)
    if (results[i].exit_code != kExitOk && !skipped[i])
      std::fprintf(stderr, "wefm: %s: %s\n", items[i].name.c_str(), results[i].error.c_str());
  if (args.has("summary-json")) {
    if (const int code = write_file_atomically(args.value("summary-json"), rows.dump(2) + '\n', error)) {
      std::fprintf(stderr, "wefm: %s\n", error.c_str());
      exit_code = std::max<int>(exit_code, code);
    }
  }
  if (interrupted()) exit_code = stop_exit_code();
  return exit_code;
}

}  // namespace

Command batch_command() { return {"batch", "flatten many faces in parallel (directory or list file)", run_batch}; }

}  // namespace wefm_cli
