#pragma once
// The WEFM solution process (METHOD §7): conformal solve with a two-step gauge, repeated-edge
// decisions, continuation in s (each step minimised by damped Gauss-Newton: gauss_newton.hpp,
// docs/SOLVER.md), quality.
#include <array>
#include <atomic>
#include <cmath>
#include <functional>
#include <map>
#include <vector>

#include "wefm/core/method/options.hpp"
#include "wefm/core/linalg/linear_row.hpp"
#include "wefm/core/linalg/sparse_cholesky.hpp"
#include "wefm/core/method/quality.hpp"

namespace wefm {

struct StepInfo {
  double s = 0;
  int iterations = 0;
  double rho_change = 0;
  bool converged = true;  // rho settled or the energy stopped falling (a flat valley), within the cap
};

struct Timings {
  double topology = 0, coefficients = 0, assembly = 0, analysis = 0, factorization = 0, solve = 0,
         continuation = 0, quality = 0, total = 0;
};

struct SolveReport {
  Quality quality;
  double s = 0;
  bool converged = true;
  Method method = Method::Global;
  int s_steps = 0, rho_iterations = 0;
  int abandoned_steps = 0;  // tentative continuation steps given up for shorter ones (their iterations count in rho_iterations)
  double rho_change = 0;
  FactorCounters counters;
  std::int64_t iterative_iterations = 0;
  bool auto_cut = false;         // the face was cut automatically (Options::auto_cut)
  Index auto_cut_edges = 0;       // facet edges in that cut
  double auto_cut_length = 0;     // its 3D length
  bool auto_cut_uncut_kept = false;  // annulus: the uncut layout scored better and is returned
  double auto_cut_other_score = std::nan("");  // annulus: score of the layout not kept (uncut or cut)
  bool min_beta_raised = false;  // the first layout was invalid; this one used a stronger beta floor
  double unwind = 1.0;           // < 1: the first layout overlapped itself; this one straightened gentle boundary turns
  double unwind_weight = 0;      // the boundary weight of that unwinding retry (0: none)
  double via_s = 0;              // > s: the first layout was invalid at s; this one came back down from via_s
  Index degenerate_triangles = 0;
  Timings time;
  double peak_memory_mb = 0;
};

struct FlattenResult {
  VectorXc uv;  // per use, in the input's length unit
  std::vector<EdgeMode> edge_modes;  // per edge, Auto resolved; Free for non-repeated edges
  std::vector<std::array<double, 5>> edge_scores;  // per edge, indexed by EdgeMode; NaN = not tried
  std::vector<StepInfo> steps;
  SolveReport report;
};

// Return false to cancel.
using ProgressFn = std::function<bool(double fraction, const char* stage)>;

struct FlattenInput {
  const TriMesh* mesh = nullptr;
  const Topology* topo = nullptr;
  Options options;
  std::vector<LinearRow> constraints;  // caller constraints over uses, right-hand sides in input units
  std::map<Index, EdgeMode> edge_modes; // forced modes per edge
  ProgressFn progress;
  const std::atomic<bool>* cancel = nullptr;
  double unwind = 1.0;                   // see assemble_boundary_operator (set by flatten's own retries)
  double boundary_weight_override = 0;   // > 0: replaces options.boundary_weight (the same retries)
  double via_s = 0;                      // > options.s: the continuation climbs to via_s, then steps back (the same retries)
};

// Throws Error on failure; Error(not_converged) carries no result, so callers wanting the partial
// result read FlattenResult::report.converged instead (flatten never throws for non-convergence).
FlattenResult flatten(const FlattenInput& input);

double peak_memory_mb();

}  // namespace wefm
