// wefm flatten INPUT -o OUTPUT.obj|.msh|.vtk|.vtu|.ply [options]
#include <cstdio>

#include "command.hpp"
#include "exit_codes.hpp"
#include "face_job.hpp"
#include "mesh_formats.hpp"
#include "output_paths.hpp"
#include "summary.hpp"

namespace wefm_cli {

namespace {

std::vector<OptionSpec> flatten_specs() {
  std::vector<OptionSpec> specs = {
      {"output", 'o', "OUT.obj", "UV mesh to write, format by extension: .obj (v, vt per vertex use, f v/vt), .msh, .vtk, .vtu, .ply (required)", "", false},
      {"seams", 0, "FILE", "facet edges to cut along: two 0-based vertex indices per line, # comments", "", false},
      {"topology", 0, "FILE.json", "face topology: edges, loops, outer_loop, per-edge mode (topo.json schema)", "",
       false},
      {"write-topology", 0, "FILE.json", "write the topology used (edges, loops, outer loop, decided modes)", "",
       false},
      {"report", 0, "FILE.json", "write the JSON quality report (fields: apps/README.md)", "", false},
      {"svg", 0, "FILE.svg|FILE.png", "picture of the UV domain coloured by area distortion", "", false},
      {"quiet", 'q', "", "no summary, no progress; errors still go to stderr", "", false},
  };
  for (auto& s : solver_option_specs()) specs.push_back(s);
  return specs;
}

void print_help() {
  std::printf(
      "Usage: wefm flatten INPUT -o OUTPUT.obj [options]\n\n"
      "Flattens one face (INPUT: OBJ, OFF, STL ascii/binary or PLY) into a 2D domain and writes it as\n"
      "a mesh with UVs (the 3D vertices, a UV per vertex use). Without --topology or --seams the loops are\n"
      "the mesh's boundary cycles; a closed or annular face needs --seams, --topology or --auto-cut.\n\n%s\nOptions:\n%s\n"
      "Progress goes to stderr (a bar on a terminal, 'progress:' lines otherwise); Ctrl-C cancels.\n\n%s",
      mesh_formats_help(), format_options(flatten_specs()).c_str(), exit_codes_help());
}

int run_flatten(const std::vector<std::string>& argv) {
  const auto specs = flatten_specs();
  ParsedArgs args;
  std::string error;
  FaceJob job;
  if (!parse_args(argv, specs, args, error) || (!args.help && !apply_solver_options(args, job.settings, error))) {
    std::fprintf(stderr, "wefm flatten: %s (see wefm flatten --help)\n", error.c_str());
    return kExitUsage;
  }
  if (args.help) {
    print_help();
    return kExitOk;
  }
  use_all_threads_unless_given(args, job.settings.options);
  if (args.positionals.size() != 1 || !args.has("output")) {
    std::fprintf(stderr, "wefm flatten: %s (usage: wefm flatten INPUT -o OUTPUT.obj [options])\n",
                 args.positionals.empty()  ? "missing INPUT"
                 : args.positionals.size() > 1 ? "more than one INPUT"
                                           : "missing -o OUTPUT.obj");
    return kExitUsage;
  }
  if (args.has("seams") && args.has("topology")) {
    std::fprintf(stderr, "wefm flatten: --seams and --topology exclude each other: put seam edges in the topology\n");
    return kExitUsage;
  }
  FlattenSettings& s = job.settings;
  auto opt = [&](const char* name) { return args.has(name) ? args.value(name) : std::string(); };
  s.seams_path = opt("seams");
  s.topology_path = opt("topology");
  s.write_topology_path = opt("write-topology");
  s.report_path = opt("report");
  s.svg_path = opt("svg");
  s.quiet = args.has("quiet");
  job.input = args.positionals[0];
  job.output_mesh = args.value("output");
  MeshFormat format = MeshFormat::obj;
  if (!mesh_format_of(job.output_mesh, format, error)) {
    std::fprintf(stderr, "wefm flatten: -o: %s\n", error.c_str());
    return kExitUsage;
  }
  std::vector<NamedPath> outputs = {{"-o", job.output_mesh}};
  for (const char* name : {"write-topology", "report", "svg"})
    if (args.has(name)) outputs.push_back({std::string("--") + name, args.value(name)});
  if (!check_output_paths({{"input", job.input}, {"--seams", s.seams_path}, {"--topology", s.topology_path}}, outputs,
                          error)) {
    std::fprintf(stderr, "wefm flatten: %s\n", error.c_str());
    return kExitUsage;
  }
  for (const std::string* out : {&job.output_mesh, &s.write_topology_path, &s.report_path, &s.svg_path}) {
    if (!out->empty() && !make_parent_dirs(*out, error)) {
      std::fprintf(stderr, "wefm: %s\n", error.c_str());
      return kExitIo;
    }
  }
  CancelWatcher watcher;  // the handlers are main()'s (stop.hpp)
  job.watcher = &watcher;
  job.show_progress = !s.quiet;
  const FaceOutcome outcome = run_face_job(job);
  if (!s.quiet && !is_stop_code(outcome.exit_code) && (outcome.snap.has_result || outcome.topology_built))
    print_summary(job.input, outcome);
  std::fflush(stdout);
  for (const std::string& w : outcome.warnings) std::fprintf(stderr, "wefm: warning: %s\n", w.c_str());
  if (outcome.exit_code == kExitSolver && outcome.snap.has_result)
    std::fprintf(stderr, "wefm: warning: %s\n", outcome.error.c_str());
  else if (outcome.exit_code != kExitOk)
    std::fprintf(stderr, "wefm: %s\n", outcome.error.c_str());
  return outcome.exit_code;
}

}  // namespace

Command flatten_command() { return {"flatten", "flatten one face to a UV mesh: OBJ, MSH, VTK, VTU or PLY (+ report, picture, topology)", run_flatten}; }

}  // namespace wefm_cli
