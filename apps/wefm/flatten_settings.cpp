#include "flatten_settings.hpp"

#include <algorithm>
#include <cstdio>
#include <thread>

#include "names.hpp"
#include "stop.hpp"

namespace wefm_cli {

namespace {

std::string num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

bool get_double(const ParsedArgs& args, const char* name, double& out, std::string& error) {
  if (!args.has(name)) return true;
  if (parse_double(args.value(name), out)) return true;
  error = std::string("--") + name + ": expected a number, got '" + args.value(name) + "'";
  return false;
}

bool get_int(const ParsedArgs& args, const char* name, int& out, std::string& error) {
  if (!args.has(name)) return true;
  long long v = 0;
  if (parse_int(args.value(name), v) && v >= -2147483647LL && v <= 2147483647LL) {
    out = static_cast<int>(v);
    return true;
  }
  error = std::string("--") + name + ": expected an integer, got '" + args.value(name) + "'";
  return false;
}

// The library's own range checks, on a face made for nothing else, before any input is read: a
// command over a CAD model would otherwise import it (minutes on a large one) and then fail every
// face with the same message.
bool library_accepts(const wefm_options& o, std::string& error) {
  wefm_face* probe = nullptr;
  if (wefm_face_create(&probe) != WEFM_OK) return true;  // no memory for a handle: the run says so itself
  const bool ok = wefm_face_set_options(probe, &o) == WEFM_OK;
  if (!ok) error = std::string("invalid option: ") + wefm_face_last_error(probe);
  wefm_face_release(probe);
  return ok;
}

}  // namespace

std::vector<OptionSpec> solver_option_specs() {
  wefm_options d;
  wefm_options_init(&d);
  return {
      {"s", 0, "S", "target roll-out exponent in [0,2]: 0 conformal, 1 altitude, 2 area", num(d.s), false},
      {"k", 0, "K", "weight normalisation exponent in [0,1] (1 or 0.5 usual)", num(d.k), false},
      {"boundary-weight", 0, "MU", "weight of the boundary term (>= 0)", num(d.boundary_weight), false},
      {"method", 0, "global|rollout", "global least squares or iterative roll-out", method_name(d.method), false},
      {"no-curvature-adjust", 0, "", "do not scale beta by Theta/2pi at interior uses",
       d.curvature_adjust ? "adjust" : "no adjust", false},
      {"s-step", 0, "DS", "largest continuation step in s (0.001 <= DS <= 2); a step up by more than 1 is retaken in steps of 1 where Gauss-Newton cuts a step short", num(d.s_step), false},
      {"rho-tolerance", 0, "TOL", "end the last continuation step below this relative rho change (earlier steps at 10x)", num(d.rho_tolerance), false},
      {"max-rho-iterations", 0, "N", "Gauss-Newton iterations per s step before reporting non-convergence",
       std::to_string(d.max_rho_iterations), false},
      {"min-beta", 0, "B", "altitude/base floor for degenerate triangles (> 0)", num(d.min_beta), false},
      {"residual", 0, "half-edge|use", "surface term: each prediction's error squared, or eq. 7's sum per use",
       d.residual == WEFM_RESIDUAL_PER_USE ? "use" : "half-edge", false},
      {"solver", 0, "auto|cholmod|eigen", "sparse factorisation", solver_name(d.solver), false},
      {"edge-mode", 0, "MODE", "mode of repeated edges not set per edge: auto|free|periodic|scar|rotational",
       edge_mode_name(d.default_edge_mode), false},
      {"edge-mode-of", 0, "EDGE=MODE",
       "force one edge's mode; EDGE is the topology file's id with --topology, else the library edge index", "",
       true},
      {"auto-cut", 0, "", "cut annuli and closed genus-0 faces automatically (no --seams/--topology)", d.auto_cut ? "on" : "off", false},
      {"threads", 0, "N", "threads of one face's solve (0 = 1); the layout is the same for any count",
       "flatten, mesh: the machine's threads; batch, model, mesh-model: " + std::to_string(d.threads > 1 ? d.threads : 1), false},
      {"memory-limit", 0, "MB", "refuse a solve estimated above MB megabytes (exit 5; 0 = no limit)", num(d.memory_limit_mb), false},
      {"score-threshold", 0, "T", "stop after the conformal solve if its score >= T (2 = never)",
       num(d.score_threshold), false},
      {"outer-loop", 0, "N", "outer loop: loop index of --topology, else boundary-cycle index; -1 automatic",
       "from --topology, else automatic", false},
      {"time-limit", 0, "SECONDS",
       "end the whole command within SECONDS (reading, CAD import, solves, outputs): exit 7, previous outputs kept",
       "none; a CAD import alone is given " + num(kDefaultImportSeconds) + " s", false},
  };
}

bool apply_solver_options(const ParsedArgs& args, FlattenSettings& settings, std::string& error) {
  wefm_options& o = settings.options;
  wefm_options_init(&o);
  if (!get_double(args, "s", o.s, error) || !get_double(args, "k", o.k, error) ||
      !get_double(args, "boundary-weight", o.boundary_weight, error) ||
      !get_double(args, "s-step", o.s_step, error) || !get_double(args, "rho-tolerance", o.rho_tolerance, error) ||
      !get_int(args, "max-rho-iterations", o.max_rho_iterations, error) ||
      !get_double(args, "min-beta", o.min_beta, error) || !get_int(args, "threads", o.threads, error) ||
      !get_double(args, "score-threshold", o.score_threshold, error) ||
      !get_double(args, "memory-limit", o.memory_limit_mb, error))
    return false;
  if (args.has("no-curvature-adjust")) o.curvature_adjust = 0;
  if (args.has("auto-cut")) o.auto_cut = 1;
  if (args.has("method")) {
    const std::string& m = args.value("method");
    if (m == "global") o.method = WEFM_METHOD_GLOBAL;
    else if (m == "rollout") o.method = WEFM_METHOD_ROLLOUT;
    else {
      error = "--method: expected global or rollout, got '" + m + "'";
      return false;
    }
  }
  if (args.has("residual")) {
    const std::string& m = args.value("residual");
    if (m == "half-edge") o.residual = WEFM_RESIDUAL_PER_HALF_EDGE;
    else if (m == "use") o.residual = WEFM_RESIDUAL_PER_USE;
    else {
      error = "--residual: expected half-edge or use, got '" + m + "'";
      return false;
    }
  }
  if (args.has("solver")) {
    const std::string& m = args.value("solver");
    if (m == "auto") o.solver = WEFM_SOLVER_AUTO;
    else if (m == "cholmod") o.solver = WEFM_SOLVER_CHOLMOD;
    else if (m == "eigen") o.solver = WEFM_SOLVER_EIGEN;
    else {
      error = "--solver: expected auto, cholmod or eigen, got '" + m + "'";
      return false;
    }
  }
  if (args.has("edge-mode") && !parse_edge_mode(args.value("edge-mode"), o.default_edge_mode)) {
    error = "--edge-mode: expected auto, free, periodic, scar or rotational, got '" + args.value("edge-mode") + "'";
    return false;
  }
  if (args.has("edge-mode-of")) {
    for (const auto& item : args.values.at("edge-mode-of")) {
      const size_t eq = item.find('=');
      long long edge = 0;
      int mode = 0;
      if (eq == std::string::npos || !parse_int(item.substr(0, eq), edge) ||
          !parse_edge_mode(item.substr(eq + 1), mode)) {
        error = "--edge-mode-of: expected EDGE=MODE (e.g. 3=periodic), got '" + item + "'";
        return false;
      }
      settings.edge_modes.emplace_back(edge, mode);
    }
  }
  if (args.has("outer-loop")) {
    if (!get_int(args, "outer-loop", settings.outer_loop, error)) return false;
    settings.has_outer_loop = true;
  }
  if (args.has("time-limit")) {
    double seconds = 0;
    if (!get_double(args, "time-limit", seconds, error)) return false;
    if (!(seconds > 0) || seconds > 1e9) {
      error = "--time-limit: expected seconds > 0, got '" + args.value("time-limit") + "'";
      return false;
    }
    // The commands parse their options first thing, so the deadline counts from the start.
    set_time_limit(seconds);
  }
  return library_accepts(o, error);
}

void use_all_threads_unless_given(const ParsedArgs& args, wefm_options& options) {
  if (!args.has("threads")) options.threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
}

}  // namespace wefm_cli
