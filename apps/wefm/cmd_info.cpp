// wefm info INPUT [--json]: what a user checks before flattening.
#include <cstdio>
#include <nlohmann/json.hpp>

#include "args.hpp"
#include "command.hpp"
#include "exit_codes.hpp"
#include "stop.hpp"
#include "wefm/wefm.h"

namespace wefm_cli {

namespace {

std::vector<OptionSpec> info_specs() {
  return {{"json", 0, "", "print one JSON object instead of the table", "", false},
          {"merge-tolerance", 0, "TOL", "STL vertex merge distance relative to the bbox diagonal (<= 0: 1e-9)", "0",
           false}};
}

void print_json(const std::string& path, const wefm_mesh_info& m) {
  nlohmann::ordered_json j;
  j["file"] = path;
  j["vertices"] = m.vertices;
  j["triangles"] = m.triangles;
  j["boundary_loops"] = m.boundary_loops;
  j["components"] = m.components;
  j["genus"] = m.genus;
  j["non_manifold_edges"] = m.non_manifold_edges;
  j["non_manifold_vertices"] = m.non_manifold_vertices;
  j["degenerate_triangles"] = m.degenerate_triangles;
  j["duplicate_triangles"] = m.duplicate_triangles;
  j["inconsistent_edges"] = m.inconsistent_edges;
  j["merged_vertices"] = m.merged_vertices;
  j["bbox_min"] = {m.bbox_min[0], m.bbox_min[1], m.bbox_min[2]};
  j["bbox_max"] = {m.bbox_max[0], m.bbox_max[1], m.bbox_max[2]};
  j["area"] = m.area;
  j["mean_edge_length"] = m.mean_edge_length;
  std::printf("%s\n", j.dump(2).c_str());
}

void print_table(const std::string& path, const wefm_mesh_info& m) {
  auto row = [](const char* name, long long v) { std::printf("  %-22s %lld\n", name, v); };
  std::printf("%s\n", path.c_str());
  row("vertices", m.vertices);
  row("triangles", m.triangles);
  row("boundary loops", m.boundary_loops);
  row("components", m.components);
  if (m.genus >= 0) row("genus", m.genus);
  else std::printf("  %-22s %s\n", "genus", "- (non-manifold)");
  row("non-manifold edges", m.non_manifold_edges);
  row("non-manifold vertices", m.non_manifold_vertices);
  row("degenerate triangles", m.degenerate_triangles);
  row("duplicate triangles", m.duplicate_triangles);
  row("inconsistent edges", m.inconsistent_edges);
  row("merged vertices", m.merged_vertices);
  std::printf("  %-22s (%.9g, %.9g, %.9g) .. (%.9g, %.9g, %.9g)\n", "bbox", m.bbox_min[0], m.bbox_min[1], m.bbox_min[2],
              m.bbox_max[0], m.bbox_max[1], m.bbox_max[2]);
  std::printf("  %-22s %.9g\n", "area", m.area);
  std::printf("  %-22s %.9g\n", "mean edge length", m.mean_edge_length);
}

int run_info(const std::vector<std::string>& argv) {
  const auto specs = info_specs();
  ParsedArgs args;
  std::string error;
  if (!parse_args(argv, specs, args, error)) {
    std::fprintf(stderr, "wefm info: %s (see wefm info --help)\n", error.c_str());
    return kExitUsage;
  }
  if (args.help) {
    std::printf("Usage: wefm info INPUT [--json]\n\nReads a mesh (OBJ, OFF, STL, PLY) and prints its counts, "
                "defects, bounding box, area and mean edge length.\n\nOptions:\n%s\n%s",
                format_options(specs).c_str(), exit_codes_help());
    return kExitOk;
  }
  if (args.positionals.size() != 1) {
    std::fprintf(stderr, "wefm info: expected exactly one INPUT (usage: wefm info INPUT [--json])\n");
    return kExitUsage;
  }
  double tolerance = 0;
  if (args.has("merge-tolerance") && !parse_double(args.value("merge-tolerance"), tolerance)) {
    std::fprintf(stderr, "wefm info: --merge-tolerance: expected a number, got '%s'\n",
                 args.value("merge-tolerance").c_str());
    return kExitUsage;
  }
  const std::string& path = args.positionals[0];
  wefm_mesh* mesh = nullptr;
  const wefm_status st = wefm_mesh_read(path.c_str(), tolerance, &mesh);
  if (st != WEFM_OK) {
    std::fprintf(stderr, "wefm: cannot read %s: %s [%s]\n", path.c_str(), wefm_last_error(), wefm_status_string(st));
    return st == WEFM_ERROR_INVALID_MESH ? kExitInvalid : kExitIo;
  }
  if (interrupted()) {  // the read cannot be interrupted; what it found is not printed after a stop
    wefm_mesh_release(mesh);
    std::fprintf(stderr, "wefm: %s: %s\n", path.c_str(), stop_reason().c_str());
    return stop_exit_code();
  }
  wefm_mesh_info info;
  wefm_mesh_info_init(&info);
  const wefm_status g = wefm_mesh_get_info(mesh, &info);
  wefm_mesh_release(mesh);
  if (g != WEFM_OK) {
    std::fprintf(stderr, "wefm: %s: %s\n", path.c_str(), wefm_last_error());
    return exit_code_for(g);
  }
  if (args.has("json")) print_json(path, info);
  else print_table(path, info);
  return kExitOk;
}

}  // namespace

Command info_command() { return {"info", "print a mesh's counts, defects, bounding box and area", run_info}; }

}  // namespace wefm_cli
