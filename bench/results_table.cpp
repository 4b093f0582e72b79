#include "results_table.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <tuple>
#include <vector>

namespace wefm_bench {

namespace {

double get(const Json& j, const char* key, double fallback = NAN) {
  auto it = j.find(key);
  return it != j.end() && it->is_number() ? it->get<double>() : fallback;
}

std::string fmt(double v, const char* f = "%.3g") {
  if (!std::isfinite(v)) return "–";
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

// Seconds with a precision that reads well from milliseconds to minutes.
std::string sec(double v) {
  if (!std::isfinite(v)) return "–";
  if (v < 0.0995) return fmt(v * 1000, "%.1f ms");
  if (v < 99.5) return fmt(v, "%.2f");
  return fmt(v, "%.0f");
}

std::string key_of(const Json& c) { return c.value("shape", "") + "/" + c.value("size", ""); }

bool ok_case(const Json& c) { return !c.value("timed_out", false) && c.contains("vertices"); }

const Json* find_case(const Json& cases, const char* kind, const std::string& key, double s = NAN) {
  for (const Json& c : cases)
    if (c.value("kind", "") == kind && key_of(c) == key && (std::isnan(s) || get(c, "s") == s) && ok_case(c)) return &c;
  return nullptr;
}

// Total library time of a wefm case, and the stages that do not overlap (continuation contains
// assembly, factorisation, solves and quality of its own steps, so it is shown but not summed).
struct Stages {
  double mesh_topology, coefficients, assembly, analysis, factorization, solve, quality, other, continuation, total;
};

Stages stages_of(const Json& c) {
  Stages s{};
  const Json& r = c.contains("report") ? c["report"] : Json::object();
  s.mesh_topology = get(c, "time_set_mesh") + get(c, "time_build");
  s.coefficients = get(r, "time_coefficients");
  s.assembly = get(r, "time_assembly");
  s.analysis = get(r, "time_analysis");
  s.factorization = get(r, "time_factorization");
  s.solve = get(r, "time_solve");
  s.quality = get(r, "time_quality");
  s.continuation = get(r, "time_continuation");
  s.total = get(c, "time_library");
  s.other = get(c, "time_solve_wall") - (s.coefficients + s.assembly + s.analysis + s.factorization + s.solve + s.quality);
  return s;
}

double cgal_cpu(const Json& c) {
  const double v = get(c, "cpu_parameterize");
  return std::isfinite(v) ? v : get(c, "cpu_user") + get(c, "cpu_sys");
}

// CPU seconds of the library calls; older results only have the whole process's.
double cpu_library(const Json& c) {
  const double v = get(c, "cpu_library");
  return std::isfinite(v) ? v : get(c, "cpu_user") + get(c, "cpu_sys");
}

std::string row(const std::vector<std::string>& cells) {
  std::string r = "|";
  for (const auto& c : cells) r += " " + c + " |";
  return r + "\n";
}

}  // namespace

void add_scaling_exponents(Json& results) {
  Json out = Json::array();
  const Json& cases = results["cases"];
  // series -> (triangles, seconds) in the order the sizes were run
  std::map<std::string, std::vector<std::tuple<double, double, std::string>>> series;
  for (const Json& c : cases) {
    if (!ok_case(c)) continue;
    const std::string kind = c.value("kind", "");
    double t = NAN, cpu = NAN;
    std::string name;
    if (kind == "wefm" && c.contains("report")) {
      t = get(c, "time_library");
      cpu = get(c, "cpu_library");
      name = "wefm s=" + fmt(get(c, "s"), "%g") + ", " + c.value("shape", "");
    } else if (kind == "floor") {
      t = get(c, "time_floor");
      cpu = get(c, "cpu_floor");
      name = "floor, " + c.value("shape", "");
    } else if (kind == "cgal") {
      t = get(c, "time_parameterize");
      cpu = get(c, "cpu_parameterize");
      name = "CGAL LSCM, " + c.value("shape", "");
    } else {
      continue;
    }
    // CPU time does not count waiting for a core, so on a shared machine its exponent is the sound one.
    if (std::isfinite(cpu)) series[name + " (CPU)"].emplace_back(get(c, "triangles"), cpu, c.value("size", ""));
    series[name].emplace_back(get(c, "triangles"), t, c.value("size", ""));
  }
  for (auto& [name, pts] : series) {
    std::sort(pts.begin(), pts.end());
    for (size_t k = 0; k + 1 < pts.size(); ++k) {
      const auto& [n1, t1, l1] = pts[k];
      const auto& [n2, t2, l2] = pts[k + 1];
      if (n1 < 50000 || !(n2 > n1) || !(t1 > 0) || !(t2 > 0)) continue;  // 10k is too small to say anything
      out.push_back({{"series", name}, {"from", l1}, {"to", l2}, {"exponent", std::log(t2 / t1) / std::log(n2 / n1)}});
    }
  }
  results["exponents"] = out;
}

std::string markdown_tables(const Json& results) {
  const Json& cases = results["cases"];
  std::string md;
  md += "Machine: " + results.value("machine", "?") + "  \n";
  if (results.contains("glibc_tunables")) md += "Every case ran with `GLIBC_TUNABLES=" + results.value("glibc_tunables", "") + "`  \n";
  if (results.contains("threads"))
    md += "wefm ran with `threads` = " + std::to_string(results.value("threads", 1)) +
          " (library cases and `wefm flatten --threads`)  \n";
  md += "Date: " + results.value("date", "?") + "; wefm " + results.value("wefm_version", "?") + "; load average " +
        fmt(get(results, "load_start"), "%.2f") + " at start, " + fmt(get(results, "load_end"), "%.2f") + " at end  \n";
  md += "Command: `" + results.value("command", "?") + "`\n\n";

  md += "### wefm per stage (seconds)\n\n";
  md += "`mesh+topo` is `wefm_face_set_mesh` + `wefm_face_build` (validation, half-edges, uses), timed by the benchmark; "
        "the next six columns are the solve report's timers; `other` is the solve's wall time they do not cover; "
        "`contin.` is the report's continuation time, which *contains* the assembly, factorisations, solves and quality "
        "of the continuation steps (not summed). `total` = mesh+topo + solve wall. `×floor` = total / Laplacian floor "
        "of the same face. `CPU` is the CPU time (all threads) of the library calls (the whole case process's user+sys, "
        "face generation included, in results without it), `CPU ×floor` the same ratio in CPU time, and `load` the "
        "1-minute load average when the case started: on a shared machine a wall time far above the CPU time means the "
        "case waited for a core, and the CPU figures are the ones to compare. `wefm/CGAL` is total / CGAL LSCM time, wall (CPU). "
        "`an/fac/sol` are the report's counters.\n\n";
  md += row({"face", "triangles", "s", "mesh+topo", "coeff.", "assembly", "analysis", "factor.", "solves", "quality", "other",
             "contin.", "**total**", "×floor", "CPU", "CPU ×floor", "load", "peak MB", "wefm/CGAL", "an/fac/sol", "status"});
  md += row({"---", "--:", "--:", "--:", "--:", "--:", "--:", "--:", "--:", "--:", "--:", "--:", "--:", "--:", "--:", "--:", "--:", "--:", "--:",
             "--:", "---"});
  for (const Json& c : cases) {
    if (c.value("kind", "") != "wefm") continue;
    const std::string key = key_of(c);
    if (!ok_case(c)) {
      const std::string why = c.value("timed_out", false) ? "timed out after " + sec(get(c, "wall")) + " s" : "crashed: " + c.value("error", "?");
      md += row({c.value("shape", ""), c.value("size", ""), fmt(get(c, "s"), "%g"), "", "", "", "", "", "", "", "", "", "–", "", "", "",
                 "", "", "", "", why});
      continue;
    }
    const Stages s = stages_of(c);
    const Json* floor = find_case(cases, "floor", key);
    const Json* cgal = find_case(cases, "cgal", key);
    const Json& r = c.contains("report") ? c["report"] : Json::object();
    const double floor_t = floor ? get(*floor, "time_floor") : NAN;
    const double cgal_t = cgal ? get(*cgal, "time_parameterize") : NAN;
    std::string status = c.value("status", "?");
    if (status == "WEFM_OK") status = "ok";
    else if (status == "WEFM_ERROR_NOT_CONVERGED") status = "not converged (s reached " + fmt(get(r, "s_reached"), "%g") + ")";
    md += row({c.value("shape", ""), fmt(get(c, "triangles"), "%.0f"), fmt(get(c, "s"), "%g"), sec(s.mesh_topology), sec(s.coefficients),
               sec(s.assembly), sec(s.analysis), sec(s.factorization), sec(s.solve), sec(s.quality), sec(s.other), sec(s.continuation),
               "**" + sec(s.total) + "**", fmt(s.total / floor_t, "%.1f"), sec(cpu_library(c)),
               floor ? fmt(cpu_library(c) / get(*floor, "cpu_floor"), "%.1f") : "–",
               fmt(get(c, "load_before"), "%.1f"), fmt(get(c, "peak_rss_mb"), "%.0f"),
               cgal ? fmt(s.total / cgal_t, "%.2f") + " (" + fmt(cpu_library(c) / cgal_cpu(*cgal), "%.2f") + ")" : "–",
               fmt(get(r, "symbolic_analyses"), "%.0f") + "/" + fmt(get(r, "numeric_factorizations"), "%.0f") + "/" +
                   fmt(get(r, "solves"), "%.0f"),
               status});
  }

  bool any_stage_cpu = false;
  for (const Json& c : cases) any_stage_cpu |= c.value("kind", "") == "wefm" && ok_case(c) && c.contains("progress_stages_cpu");
  if (any_stage_cpu) {
    static const char* kStages[] = {"coefficients", "assembly", "factorise", "solve", "repeated edges", "continuation", "rollout", "quality"};
    md += "\n### Where the solve spends its time, by progress stage (CPU seconds, share of the solve)\n\n";
    md += "From the progress callback: each stage runs from the callback naming it to the next one. `factorise` is "
          "`set_matrix` (K_PP extraction, analysis, factorisation); `solve` the constrained solves of the conformal layout "
          "with both gauges; `continuation` every rho step. CPU time, so it holds on a loaded machine.\n\n";
    std::vector<std::string> head{"face", "triangles", "s"}, align{"---", "--:", "--:"};
    for (const char* st : kStages) {
      head.push_back(st);
      align.push_back("--:");
    }
    md += row(head) + row(align);
    for (const Json& c : cases) {
      if (c.value("kind", "") != "wefm" || !ok_case(c) || !c.contains("progress_stages_cpu")) continue;
      const Json& pc = c["progress_stages_cpu"];
      double sum = 0;
      for (const auto& kv : pc.items()) sum += kv.value().get<double>();
      std::vector<std::string> cells{c.value("shape", ""), fmt(get(c, "triangles"), "%.0f"), fmt(get(c, "s"), "%g")};
      for (const char* st : kStages) {
        const double v = get(pc, st);
        cells.push_back(std::isfinite(v) ? sec(v) + " (" + fmt(100 * v / sum, "%.0f") + "%)" : "–");
      }
      md += row(cells);
    }
  }

  md += "\n### Floor and peer (seconds)\n\n";
  md += "Floor: CHOLMOD (supernodal, default ordering) on the real cotangent Laplacian with vertex 0 pinned: symbolic "
        "analysis + numeric factorisation + one solve (assembly not included). `complex` is the same matrix stored as "
        "complex, what an n×n Hermitian formulation would pay. CGAL: `Surface_mesh_parameterization::LSCM_parameterizer_3` "
        "(default solver), `parameterize` call only; `build` is converting the arrays to a `Surface_mesh`.\n\n";
  md += row({"face", "triangles", "ordering", "analysis", "factor.", "solve", "**floor**", "floor CPU", "floor peak MB", "complex floor",
             "CGAL build", "**CGAL LSCM**", "CGAL CPU", "CGAL peak MB", "CGAL / floor"});
  md += row({"---", "--:", "---", "--:", "--:", "--:", "--:", "--:", "--:", "--:", "--:", "--:", "--:", "--:", "--:"});
  std::vector<std::string> keys;
  for (const Json& c : cases)
    if (c.value("kind", "") == "floor" && ok_case(c)) keys.push_back(key_of(c));
  for (const std::string& key : keys) {
    const Json& f = *find_case(cases, "floor", key);
    const Json* fc = find_case(cases, "floor_complex", key);
    const Json* cg = find_case(cases, "cgal", key);
    const double cgal_t = cg ? get(*cg, "time_parameterize") : NAN;
    std::string cgal_cell = cg ? "**" + sec(cgal_t) + "**" : "–";
    if (cg && cg->value("status", "") != "ok") cgal_cell = cg->value("status", "failed");
    md += row({f.value("shape", ""), fmt(get(f, "triangles"), "%.0f"), f.value("ordering", ""), sec(get(f, "time_analysis")),
               sec(get(f, "time_factorization")), sec(get(f, "time_solve")), "**" + sec(get(f, "time_floor")) + "**", sec(get(f, "cpu_floor")),
               fmt(get(f, "peak_rss_mb"), "%.0f"), fc ? sec(get(*fc, "time_floor")) : "–", cg ? sec(get(*cg, "time_build")) : "–", cgal_cell,
               cg ? sec(cg->contains("cpu_parameterize") ? get(*cg, "cpu_parameterize") : get(*cg, "cpu_user") + get(*cg, "cpu_sys")) : "–",
               cg ? fmt(get(*cg, "peak_rss_mb"), "%.0f") : "–", fmt(cgal_t / get(f, "time_floor"), "%.1f")});
  }

  if (results.contains("exponents") && !results["exponents"].empty()) {
    md += "\n### Scaling exponents\n\n`log(t2/t1) / log(n2/n1)` on the total time (wall, and CPU where measured), n = triangles.\n\n";
    md += row({"series", "from", "to", "exponent"});
    md += row({"---", "---", "---", "--:"});
    for (const Json& e : results["exponents"])
      md += row({e.value("series", ""), e.value("from", ""), e.value("to", ""), fmt(get(e, "exponent"), "%.2f")});
  }

  if (results.contains("cli") && !results["cli"].empty()) {
    md += "\n### Whole process: `wefm flatten IN.obj -o OUT.obj`\n\n";
    md += "Wall time, CPU time (all threads) and peak memory of the `wefm` process (from `wait4`); read "
          "(`wefm_mesh_read`), setup (mesh info, face, topology) and solve from its `--report`; `write+exit` is the rest: "
          "writing the UV OBJ (its writer alone: the File I/O table), the report, freeing and process exit.\n\n";
    md += row({"face", "triangles", "s", "**process**", "CPU", "read OBJ", "setup", "solve", "write+exit", "peak MB", "×floor", "×CGAL", "status"});
    md += row({"---", "--:", "--:", "--:", "--:", "--:", "--:", "--:", "--:", "--:", "--:", "--:", "---"});
    for (const Json& c : results["cli"]) {
      const std::string key = key_of(c);
      const Json* floor = find_case(cases, "floor", key);
      const Json* cg = find_case(cases, "cgal", key);
      const double wall = get(c, "wall");
      const double read = get(c, "read_input"), setup = get(c, "setup"), solve = get(c, "wall_solve");
      md += row({c.value("shape", ""), fmt(get(c, "triangles"), "%.0f"), fmt(get(c, "s"), "%g"), "**" + sec(wall) + "**",
                 sec(get(c, "cpu_user") + get(c, "cpu_sys")), sec(read), sec(setup), sec(solve), sec(wall - read - setup - solve),
                 fmt(get(c, "max_rss_mb"), "%.0f"), floor ? fmt(wall / get(*floor, "time_floor"), "%.1f") : "–",
                 cg ? fmt(wall / get(*cg, "time_parameterize"), "%.2f") : "–", c.value("status", "")});
    }
  }

  bool any_io = false;
  for (const Json& c : cases) any_io |= c.value("kind", "") == "io" && ok_case(c);
  if (any_io) {
    md += "\n### File I/O (`wefm_mesh_read`; the `wefm` tool's UV OBJ writer; files in the page cache)\n\n";
    md += "Wall / CPU seconds. The STL is binary (float32 corners, unshared), so reading it includes merging the "
          "corners back into vertices; `merged` is `wefm_mesh_info.merged_vertices`.\n\n";
    md += row({"face", "triangles", "OBJ MB", "read OBJ", "UV OBJ MB", "write UV OBJ", "STL MB", "read STL", "merged", "status"});
    md += row({"---", "--:", "--:", "--:", "--:", "--:", "--:", "--:", "--:", "---"});
    auto wc = [&](const Json& c, const char* step) {
      return sec(get(c, (std::string("time_") + step).c_str())) + " / " + sec(get(c, (std::string("cpu_") + step).c_str()));
    };
    for (const Json& c : cases)
      if (c.value("kind", "") == "io" && ok_case(c))
        md += row({c.value("shape", ""), fmt(get(c, "triangles"), "%.0f"), fmt(get(c, "obj_mb"), "%.1f"), wc(c, "read_obj"),
                   fmt(get(c, "uv_obj_mb"), "%.1f"), wc(c, "write_uv_obj"), fmt(get(c, "stl_mb"), "%.1f"), wc(c, "read_stl"),
                   fmt(get(c, "stl_merged_vertices"), "%.0f"), c.value("status", "")});
  }
  return md;
}

}  // namespace wefm_bench
