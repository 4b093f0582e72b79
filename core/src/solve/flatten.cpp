#include "wefm/core/solve/flatten.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cmath>
#include <utility>
#include <fstream>
#include <limits>
#include <optional>
#include <string>
#include <system_error>
#include <tuple>

#include "wefm/core/method/caller_rows.hpp"
#include "wefm/core/solve/early_analysis.hpp"
#include "wefm/core/method/energy.hpp"
#include "wefm/core/sys/error.hpp"
#include "wefm/core/method/gauge.hpp"
#include "wefm/core/solve/gauss_newton.hpp"
#include "wefm/core/method/seam_substitution.hpp"
#include "wefm/core/method/repeated_edges.hpp"
#include "wefm/core/method/rollout.hpp"

namespace wefm {

namespace {

double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

// Continuation steps below the target s end at this multiple of rho_tolerance.
constexpr double kWayUpTolerance = 10.0;

// A mode candidate this close to the best one's score (or better) is solved again with
// refinement before the choice; the rest are judged unrefined.
constexpr double kRefineMargin = 1e-6;

class Stage {
 public:
  Stage(const FlattenInput& in) : in_(in) {}
  void check(double fraction, const char* stage) const {
    if (in_.cancel && in_.cancel->load(std::memory_order_relaxed)) fail(Errc::cancelled, std::string("cancelled during ") + stage);
    if (in_.progress && !in_.progress(fraction, stage)) fail(Errc::cancelled, std::string("cancelled by the progress callback during ") + stage);
  }

 private:
  const FlattenInput& in_;
};


}  // namespace

double peak_memory_mb() {
  std::ifstream f("/proc/self/status");
  std::string line;
  while (std::getline(f, line))
    if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;
  return 0.0;
}

namespace {

// The caller's rows are bounded (caller_rows.hpp) and the mesh's size is checked, so a non-finite
// layout is a bug: reported as one, never returned as a result.
void require_finite(const VectorXc& uv) {
  if (!uv.allFinite()) fail(Errc::internal, "the solve produced a layout with non-finite coordinates");
}

FlattenResult flatten_attempt(const FlattenInput& in) {
  const double t_start = now();
  const TriMesh& mesh = *in.mesh;
  const Topology& tp = *in.topo;
  const Options& opt = in.options;
  validate_options(opt);
  // The factorisation's BLAS and OpenMP run on one thread whatever opt.threads: 2 threads were no
  // faster (1M disk, s = 0: 3.4-3.6 s against 2.7-3.3 s), their wake-ups spin on a busy machine,
  // and their sums' order would make the layout depend on the thread count.
  set_blas_threads(1);
  Stage stage(in);
  FlattenResult res;
  SolveReport& rep = res.report;
  rep.method = opt.method;
  stage.check(0.0, "coefficients");

  const int threads = std::max(1, opt.threads);
  double t0 = 0;
  const double mu = in.boundary_weight_override > 0 ? in.boundary_weight_override : opt.boundary_weight;
  PartitionedKKT kkt(opt.backend);
  kkt.factor().set_threads(opt.threads);
  // memory_limit_mb: the factor's values (CHOLMOD's xsize from the analysis) plus 0.75 KB per
  // triangle for the rest. Measured peaks of whole `wefm flatten` runs, 1M-triangle disk (factor
  // 34.1M entries) and plate (26.7M), s = 0, 1, 2: 0.59-0.85 KB per triangle besides the factor,
  // so the estimate (disk 1295 MB, plate 1177 MB) is within -8% .. +16% of the peak there.
  const double other_mb = 0.75e-3 * static_cast<double>(mesh.triangles.size());
  kkt.factor().set_memory_limit(opt.memory_limit_mb, other_mb);
  // The split uses and the points for the ordering, should minimum degree's fill be poor
  // (nested_dissection.hpp): the global method's.
  const bool global = opt.method == Method::Global;
  const auto split = global ? far_pair_3d(mesh, tp, tp.outer_loop) : std::pair<Index, Index>{0, 0};
  std::vector<Vec3> at(global ? static_cast<size_t>(tp.use_count) : 0);
  for (size_t u = 0; u < at.size(); ++u) at[u] = mesh.vertices[static_cast<size_t>(tp.use_vertex[u])];
  // K's analysis side by side with the coefficients and K's values (early_analysis.hpp). Measured
  // at 1M triangles, s = 0: see docs/PERFORMANCE.md.
  std::unique_ptr<EnergyAssembler> assembler;
  std::optional<EarlyAnalysis> ahead;
  if (global && opt.residual == Residual::PerHalfEdge && early_analysis_pays(tp.use_count, threads)) {
    t0 = now();
    const SpMatC b_pattern = boundary_operator_pattern(mesh, tp, mu);
    assembler = std::make_unique<EnergyAssembler>(tp, b_pattern.nonZeros() ? &b_pattern : nullptr, threads);
    rep.time.assembly += now() - t0;
    try {
      ahead.emplace(*assembler, kkt, split.first, split.second, &at);
    } catch (const std::system_error&) {
      ahead.reset();  // no thread to be had: the analysis runs in turn below
    }
  }

  t0 = now();
  // While the analysis runs, one thread fewer here: it is the longer of the two (the same bits for
  // any thread count).
  const int setup_threads = ahead ? std::max(1, threads - 1) : threads;
  const Coefficients coef = compute_coefficients(mesh, tp, opt.curvature_adjust, opt.min_beta, setup_threads);
  rep.time.coefficients = now() - t0;
  rep.degenerate_triangles = coef.degenerate_triangles;
  if (coef.degenerate_triangles == static_cast<Index>(mesh.triangles.size())) {
    // Edge lengths squared overflow above about 1e154 and underflow below 1e-154: such a mesh
    // has shape, but not one double precision can measure.
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (const Tri& f : mesh.triangles)
      for (Index v : f) {
        lo = lo.cwiseMin(mesh.vertices[static_cast<size_t>(v)]);
        hi = hi.cwiseMax(mesh.vertices[static_cast<size_t>(v)]);
      }
    const double extent = (hi - lo).maxCoeff();
    if (extent > 1e150 || (extent > 0 && extent < 1e-150))
      fail(Errc::invalid_mesh, "the mesh's extent, " + message_number(extent) +
                                   ", is outside 1e-150 .. 1e150: its edge lengths squared overflow or underflow double precision; rescale the coordinates");
    fail(Errc::invalid_mesh, "every triangle of the face has zero area: there is no shape to flatten");
  }
  const double ls = coef.length_scale;
  const Eigen::VectorXd eta = Eigen::Map<const Eigen::VectorXd>(coef.use_area.data(), static_cast<Index>(coef.use_area.size()));

  const std::vector<LinearRow> caller = normalised_caller_rows(in.constraints, ls);
  const VectorXc z_ref = planar_projection(mesh, tp, ls);
  GaugeChoice gauge = choose_gauges(caller, z_ref);
  // Translation is fixed by pinning one gauge use and shifting afterwards (see PartitionedKKT::solve).
  const Eigen::VectorXd* eta_ptr = nullptr;
  auto recentre = [&](VectorXc& zz) {
    if (!gauge.translation) return;
    const Complex c = eta.cast<Complex>().dot(zz) / eta.sum();
    zz.array() -= c;
  };

  // Modes per repeated edge: forced, or the default, or Auto (decided below).
  const size_t ne = tp.edges.size();
  res.edge_modes.assign(ne, EdgeMode::Free);
  res.edge_scores.assign(ne, {std::nan(""), std::nan(""), std::nan(""), std::nan(""), std::nan("")});
  std::vector<EdgeMode> mode(ne, EdgeMode::Free);
  std::vector<Complex> rotation(ne, Complex(1, 0));
  std::vector<Index> auto_edges;
  for (const RepeatedEdge& r : tp.repeated) {
    auto it = in.edge_modes.find(r.edge);
    EdgeMode m = it != in.edge_modes.end() ? it->second : opt.default_edge_mode;
    if (m == EdgeMode::Auto) {
      auto_edges.push_back(r.edge);
      // An interior slit (both ends shared by its two sides) starts glued: started free, the
      // slits that do not want to open leave gaps of zero width, judged crossing or not by
      // rounding, and the descent took another path on another BLAS kernel (8-slit plate).
      // Not a seam that is the outer loop itself (a full sphere's pole-to-pole seam): there the
      // glued start is a closed surface, and the continuation converged less often from it.
      const auto& outer = tp.loop_uses[static_cast<size_t>(tp.outer_loop)];
      const bool slit = !r.side_a.empty() && r.side_a.front() == r.side_b.front() && r.side_a.back() == r.side_b.back() &&
                        std::find(outer.begin(), outer.end(), r.side_a.front()) == outer.end();
      m = slit ? EdgeMode::Scar : EdgeMode::Free;
    }
    mode[static_cast<size_t>(r.edge)] = m;
  }

  if (opt.method == Method::Rollout) {
    if (!tp.repeated.empty())
      for (const RepeatedEdge& r : tp.repeated)
        if (mode[static_cast<size_t>(r.edge)] != EdgeMode::Free)
          fail(Errc::unsupported, "the roll-out method supports only free repeated edges (edge " + std::to_string(r.edge) + " is not free); use the global method");
    RolloutResult rr = rollout(mesh, tp, coef, caller, opt, [&](double f) { stage.check(f, "rollout"); });
    res.uv = rr.z * ls;
    require_finite(res.uv);
    rep.iterative_iterations = rr.sweeps;
    rep.converged = rr.converged;
    rep.s = 1.0;
    t0 = now();
    rep.quality = evaluate_quality(mesh, tp, res.uv, threads);
    rep.time.quality = now() - t0;
    rep.time.total = now() - t_start;
    rep.peak_memory_mb = peak_memory_mb();
    return res;
  }

  // --- Conformal solve with the two-step gauge --------------------------------------------------
  stage.check(0.05, "assembly");
  t0 = now();
  const SpMatC B = assemble_boundary_operator(mesh, tp, coef, mu, in.unwind);
  const SpMatC* Bp = B.rows() ? &B : nullptr;
  std::vector<double> rho;  // empty: s = 0
  // K straight into its pattern, without the surface operator A (K = A^H A + B^H B): at 1M
  // triangles A cost 180 MB and two passes.
  if (ahead) ahead->copied();
  const bool foreseen = assembler && assembler->set_boundary(Bp);  // B's pattern is the one analysed
  const bool analysed = ahead && foreseen;
  SpMatC K = foreseen ? assembler->assemble(compute_weights(tp, coef, opt.k, setup_threads), compute_sigma(coef, rho, 0.0, setup_threads), setup_threads)
                      : assemble_energy(tp, coef, compute_sigma(coef, rho, 0.0, threads), opt.k, opt.residual, Bp, threads);
  assembler.reset();
  rep.time.assembly += now() - t0;
  const auto seg = longest_loop_segment(tp, mesh, tp.outer_loop);
  stage.check(0.1, "factorise");
  if (ahead) {
    const double tw = now();
    ahead->wait();
    // The analysis overlapped the coefficients and assembly: the solve's timers count only the
    // time it waited for it, so that they still add up to its wall time.
    kkt.counters().time_analysis = now() - tw;
  }
  // Analysed already, unless B's pattern was not the one foreseen (then it is analysed here).
  kkt.set_matrix(K, split.first, split.second, analysed ? nullptr : &at);
  ahead.reset();
  std::vector<Vec3>().swap(at);

  LinearRow vec, pin;
  pin.terms = {{seg.first, 1.0}};
  pin.rhs = 0.0;
  auto rows_with = [&](const std::vector<EdgeMode>& md, const std::vector<Complex>& rot, const LinearRow* vec) {
    std::vector<LinearRow> rows = caller;
    for (const RepeatedEdge& r : tp.repeated) {
      auto add = repeated_edge_rows(r, md[static_cast<size_t>(r.edge)], rot[static_cast<size_t>(r.edge)]);
      rows.insert(rows.end(), add.begin(), add.end());
    }
    if (vec) rows.push_back(*vec);
    if (gauge.translation) rows.push_back(pin);
    return rows;
  };
  if (gauge.vector) {
    const double L = (mesh.vertices[static_cast<size_t>(tp.use_vertex[static_cast<size_t>(seg.second)])] -
                      mesh.vertices[static_cast<size_t>(tp.use_vertex[static_cast<size_t>(seg.first)])]).norm() / ls;
    vec.terms = {{seg.second, 1.0}, {seg.first, -1.0}};
    vec.rhs = L;
  }
  stage.check(0.2, "solve");
  // With a vector gauge this first layout only locates the far pair below: not refined.
  VectorXc z = kkt.solve(rows_with(mode, rotation, gauge.vector ? &vec : nullptr), eta_ptr, !gauge.vector);
  recentre(z);
  if (gauge.vector) {
    // Fixing one short facet edge lets its local error tilt the whole layout; fix the vector
    // between two far-apart boundary uses instead. Same factorisation.
    const auto fp = far_pair(tp, z, tp.outer_loop);
    if (fp.first != fp.second) {
      vec.terms = {{fp.second, 1.0}, {fp.first, -1.0}};
      vec.rhs = z[fp.second] - z[fp.first];
      pin.terms = {{fp.first, 1.0}};
      pin.rhs = z[fp.first];
    }
    z = kkt.solve(rows_with(mode, rotation, &vec), eta_ptr);  // refined (without a far pair: the first gauge again)
    recentre(z);
  }
  // Scales about the gauge centre so the total UV area equals the 3D area (size-free layouts).
  auto scale_to_3d_area = [&](VectorXc& zz) {
    double uv_area = 0, a3 = 0;
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
      const Complex u0 = zz[tp.corner_use[3 * t]], u1 = zz[tp.corner_use[3 * t + 1]], u2 = zz[tp.corner_use[3 * t + 2]];
      uv_area += 0.5 * ((u1 - u0).real() * (u2 - u0).imag() - (u1 - u0).imag() * (u2 - u0).real());
      a3 += coef.tri_area[t];
    }
    if (uv_area > 0) zz = ((zz.array() - gauge.center) * std::sqrt(a3 / uv_area) + gauge.center).matrix();
  };
  Quality last_quality;
  auto score_of = [&](const VectorXc& zz) {
    const double tq = now();
    last_quality = evaluate_quality(mesh, tp, zz, threads);
    rep.time.quality += now() - tq;
    return last_quality.score;
  };

  // --- Repeated edges: choose each automatic edge's mode by score (METHOD §7 step 2) -----------
  if (!auto_edges.empty()) {
    stage.check(0.3, "repeated edges");
    std::vector<Index> seam_uses;
    for (const RepeatedEdge& r : tp.repeated) {
      seam_uses.insert(seam_uses.end(), r.side_a.begin(), r.side_a.end());
      seam_uses.insert(seam_uses.end(), r.side_b.begin(), r.side_b.end());
    }
    kkt.prepare(seam_uses, eta_ptr);
    double current = score_of(z);
    // Coordinate descent over edges: each automatic edge tries every mode with the others fixed;
    // two passes at most. Cost: 4 x edges x passes small dense solves, one factorisation in all.
    size_t last_changed = auto_edges.size();  // the edge whose mode changed last
    bool settled = false;
    for (int pass = 0; pass < 2 && !settled; ++pass) {
      bool changed = false;
      for (size_t i = 0; i < auto_edges.size(); ++i) {
        // Back at the edge that changed last: every other edge has been tried since, with the modes
        // as they are now, and kept its mode, so each would choose as before (a face with one seam
        // paid for a second pass of identical solves).
        if (pass > 0 && i == last_changed) {
          settled = true;
          break;
        }
        const Index e = auto_edges[i];
        const RepeatedEdge& r = tp.repeated[static_cast<size_t>(tp.edge_repeated[static_cast<size_t>(e)])];
        std::vector<EdgeMode> md = mode;
        md[static_cast<size_t>(e)] = EdgeMode::Free;
        // The free layout, solved once: the free candidate, and the rotation estimate of the
        // rotational one (each solve costs a few factor solves: 0.7 s at 1M triangles).
        VectorXc z_free = z;
        bool free_singular = false;
        try {
          z_free = kkt.solve(rows_with(md, rotation, gauge.vector ? &vec : nullptr), eta_ptr);
        } catch (const Error& err) {
          if (err.code() != Errc::singular) throw;
          free_singular = true;
        }
        // Ranked valid first, then by fewer flips and crossings, then by score: with several
        // edges, one edge's choice can remove a crossing while another still makes the layout
        // invalid, and a flat -2 would hide that progress from the descent.
        using Rank = std::tuple<int, std::int64_t, double>;
        // Periodic first: on ties (a developable cylinder is exact both free and periodic) the
        // periodic domain is the one a mesher wants, with matching nodes on the two sides.
        constexpr std::array<EdgeMode, 4> kOrder = {EdgeMode::Periodic, EdgeMode::Free, EdgeMode::Rotational, EdgeMode::Scar};
        std::array<Rank, 4> ranks;
        std::array<double, 4> scores{};
        std::array<std::vector<Complex>, 4> rots;
        std::array<VectorXc, 4> refined;  // the layouts solved with refinement (free always)
        // The unrefined solves, kept so that refining a contender goes on from its solve
        // (PartitionedKKT::refine) instead of repeating it: one factor solve less per contender.
        std::array<PartitionedKKT::Unrefined, 4> unrefined;
        auto try_mode = [&](size_t k, bool refine) {
          const EdgeMode cand = kOrder[k];
          md[static_cast<size_t>(e)] = cand;
          rots[k] = rotation;
          if (cand == EdgeMode::Rotational) rots[k][static_cast<size_t>(e)] = estimate_rotation(r, z_free);
          double sc;
          Rank rank;
          VectorXc zc;
          try {
            if (cand == EdgeMode::Free && free_singular) fail(Errc::singular, "free candidate");
            if (cand == EdgeMode::Free) {
              zc = z_free;
            } else {
              const std::vector<LinearRow> rows = rows_with(md, rots[k], gauge.vector ? &vec : nullptr);
              if (refine) {
                zc = unrefined[k].z.size() > 0 ? kkt.refine(rows, eta_ptr, std::move(unrefined[k])) : kkt.solve(rows, eta_ptr);
                unrefined[k] = PartitionedKKT::Unrefined{};
              } else {
                unrefined[k] = kkt.solve_unrefined(rows, eta_ptr);
                zc = unrefined[k].z;
              }
            }
            recentre(zc);
            glue_scars(tp, md, zc);
            sc = score_of(zc);
            const std::int64_t bad = last_quality.flips + last_quality.boundary_intersections;
            rank = Rank{bad == 0 ? 1 : 0, -bad, sc};
            // Sides that land on each other (a flat ring: periodic with a zero shift, rotational by
            // zero, free) are the scar, judged by rounding as touching or not: the scar candidate
            // glues them exactly, and it alone may take that layout.
            if (cand != EdgeMode::Scar && sides_coincide(r, zc)) rank = Rank{0, std::numeric_limits<std::int64_t>::min(), sc};
          } catch (const Error& err) {
            if (err.code() != Errc::singular) throw;
            sc = -std::numeric_limits<double>::infinity();
            rank = Rank{0, std::numeric_limits<std::int64_t>::min(), sc};
          }
          if (cand == EdgeMode::Free) z_free = zc;
          ranks[k] = rank;
          scores[k] = sc;
          if (refine || cand == EdgeMode::Free) refined[k] = std::move(zc);
        };
        // The best candidate in kOrder (the edge's current mode when none ranks above nothing).
        auto best_of = [&] {
          Rank best{0, std::numeric_limits<std::int64_t>::min(), -std::numeric_limits<double>::infinity()};
          int kb = -1;
          for (size_t k = 0; k < kOrder.size(); ++k) {
            // A constrained mode must beat free clearly: constraints are only worth their rigidity.
            const bool better = std::get<0>(ranks[k]) != std::get<0>(best) || std::get<1>(ranks[k]) != std::get<1>(best)
                                    ? ranks[k] > best
                                    : std::get<2>(ranks[k]) > std::get<2>(best) + 1e-9;
            if (better) {
              best = ranks[k];
              kb = static_cast<int>(k);
            }
          }
          return kb;
        };
        // Every candidate but free (refined above) is solved without refinement first, and again
        // with it only where it could matter: the winner and the valid candidates within
        // kRefineMargin of its score, or every candidate when none is valid. Refinement moves a
        // score by 5e-10 at most (1M-triangle tube), far inside the margin, so the choice is the
        // one refined candidates give; each refinement costs two factor solves (0.3 s at 1M).
        for (size_t k = 0; k < kOrder.size(); ++k) try_mode(k, false);
        const int first = best_of();
        const bool valid_best = first >= 0 && std::get<0>(ranks[static_cast<size_t>(first)]) == 1;
        for (size_t k = 0; k < kOrder.size(); ++k) {
          if (kOrder[k] == EdgeMode::Free) continue;
          const bool contender = !valid_best || (std::get<0>(ranks[k]) == 1 && scores[k] >= scores[static_cast<size_t>(first)] - kRefineMargin);
          if (contender) try_mode(k, true);
        }
        const int kb = best_of();
        for (size_t k = 0; k < kOrder.size(); ++k) {
          const double sc = scores[k];
          res.edge_scores[static_cast<size_t>(e)][static_cast<size_t>(kOrder[k])] = std::isfinite(sc) ? sc : -3.0;
        }
        EdgeMode best_mode = mode[static_cast<size_t>(e)];
        VectorXc best_z = z;
        double best_score = -std::numeric_limits<double>::infinity();
        if (kb >= 0) {
          const size_t k = static_cast<size_t>(kb);
          // A contender that refinement made invalid can leave the win to a candidate judged unrefined.
          if (refined[k].size() == 0) try_mode(k, true);
          best_mode = kOrder[k];
          best_z = std::move(refined[k]);
          best_score = scores[k];
          if (best_mode == EdgeMode::Rotational) rotation[static_cast<size_t>(e)] = rots[k][static_cast<size_t>(e)];
        }
        if (best_mode != mode[static_cast<size_t>(e)]) {
          changed = true;
          last_changed = i;
        }
        mode[static_cast<size_t>(e)] = best_mode;
        z = std::move(best_z);
        current = best_score;
      }
      if (!changed) break;
    }
    (void)current;
  }
  for (size_t e = 0; e < ne; ++e) res.edge_modes[e] = mode[e];

  // --- Continuation in s ------------------------------------------------------------------------
  const bool early = opt.s > 0 && opt.score_threshold <= 1.0 && score_of(z) >= opt.score_threshold;
  const double t_cont = now();
  // Gauss-Newton can end in a layout with flips or boundary overlaps where a smaller s gave a valid
  // one (a sphere with a small hole at s = 2): keep the valid layout of the largest s reached, and
  // report that s. Scores are not compared across s: the caller chose s, and on a sphere a valid
  // s = 0.3 layout scores below s = 0 (measured .034 against .039) yet is what was asked for.
  // Only when no step is valid does the best score win.
  auto rank_of = [&](const VectorXc& zz, double s_of) {
    const double sc = score_of(zz);
    const bool valid = last_quality.flips == 0 && last_quality.boundary_intersections == 0 && s_of <= opt.s + 1e-12;
    return std::make_pair(valid ? 1 : 0, valid ? s_of : sc);
  };
  VectorXc best_z = z;
  std::pair<int, double> best_rank = opt.s > 0 ? rank_of(z, 0.0) : std::make_pair(1, 0.0);
  double best_s = 0.0;
  FactorCounters gn_counters;
  if (opt.s > 0 && !early) {
    // For s > 0 the energy fixes the size: start from the layout with the 3D area.
    if (gauge.vector) scale_to_3d_area(z);
    const SeamSubstitution sub = substitute_seams(tp, mode, rotation);
    std::vector<LinearRow> keep;
    for (const LinearRow& r : caller) keep.push_back(reduce_row(sub, r));
    keep.insert(keep.end(), sub.leftover.begin(), sub.leftover.end());
    // The s = 0 factor becomes the continuation's preconditioner, refactorised in place; with
    // substituted seams the continuation factorises its own pattern: do not hold two factors.
    // The caches (a copy of K among them) go first, before the continuation allocates.
    kkt.release_caches();
    GaussNewton gn(tp, coef, Bp, opt.k, opt.residual, K, sub, keep, opt.backend, opt.min_beta, threads);  // takes K over (K is not needed after)
    gn.own_factor().set_threads(opt.threads);
    gn.set_threads(opt.threads);
    gn.own_factor().set_memory_limit(opt.memory_limit_mb, other_mb);
    if (!gn.share_factor(kkt.factor(), kkt.split_use(0), kkt.split_use(1))) {
      kkt.release();
      // Its own factor orders its own pattern: points for the ordering, as for K_PP (a 1M-triangle
      // cylinder's rotational seam: 2.4 s of METIS otherwise). A seam's shift sits at the mean
      // of the uses it moves.
      std::vector<Vec3> at(static_cast<size_t>(sub.reduced), Vec3::Zero());
      for (Index c = 0; c < sub.reduced; ++c) {
        int k = 0;
        for (SpMatC::InnerIterator it(sub.P, c); it; ++it, ++k)
          at[static_cast<size_t>(c)] += mesh.vertices[static_cast<size_t>(tp.use_vertex[static_cast<size_t>(it.row())])];
        if (k > 1) at[static_cast<size_t>(c)] /= k;
      }
      gn.own_factor().set_ordering_points(std::move(at));
    }
    if (gauge.vector) gn.set_gauge_row(reduce_row(sub, vec));
    gn.set_scale_center(gauge.center);
    // The s schedule: up to the target in s_step steps, or up to via_s and then back to the target.
    std::vector<double> schedule;
    const double s_top = in.via_s > opt.s ? in.via_s : opt.s;
    if (s_top > opt.s) {
      schedule.push_back(s_top);
      const double down = std::min(opt.s_step, 0.5);
      for (double sv = s_top; sv > opt.s + 1e-12;) schedule.push_back(sv = std::max(opt.s, sv - down));
    } else {
      for (double sv = 0; sv < s_top - 1e-12;) schedule.push_back(sv = std::min(s_top, sv + opt.s_step));
    }
    double s_cur = 0;
    double shown = 0.4;  // progress only moves forward, also when a tentative step gives way
    for (size_t k = 0; k < schedule.size();) {
      const double s_next = schedule[k];
      // A step up by more than 1 is tentative: it is kept only if every Gauss-Newton step on the
      // way is a full one. Where one is cut short (the flip bound or the line search), the step is
      // taken again from its start in steps of 1. Measured (docs/SOLVER.md, "Steps"): from s = 0
      // to 2 on smooth faces in half the iterations of two steps (1M plate: Gauss-Newton 8 -> 5,
      // CG 98 -> 70) to the same layout, while the faces that land elsewhere when jumping (MAT,
      // the sphere with a small hole, the bottle) all have a cut in their first step.
      // The climb to via_s is not: it is a jump on purpose (a retry after an invalid layout).
      const bool tentative = s_top == opt.s && s_next - s_cur > 1.0 + 1e-12;
      const VectorXc z_start = tentative ? z : VectorXc();
      const GaussNewton::State gn_start = gn.state();
      // A step on the way up only places the next one's start: it stops at kWayUpTolerance times
      // the tolerance. Measured at s = 2 on the real sample and the synthetic faces: the same scores
      // to 1e-4 (bottle .99330 -> .99338, helix .928282 -> .928296), Gauss-Newton iterations fewer
      // on 9 of 19 faces (revolved sphere 53 -> 49, MAT 21 -> 18), the 1M disk 7 -> 6. A single
      // predictor iteration instead cost the bottle and the sphere with a small hole (SOLVER.md).
      const bool way_up = s_top == opt.s && k + 1 < schedule.size();
      const double tol = way_up ? kWayUpTolerance * opt.rho_tolerance : opt.rho_tolerance;
      gn.set_stop_at_cut(tentative);
      const GaussNewtonReport gr = gn.run(z, s_next, tol, opt.max_rho_iterations, gauge.vector && s_next >= 1.0, [&](int it) {
        shown = std::max(shown, 0.4 + 0.5 * std::min(1.0, (s_cur + (s_next - s_cur) * it / opt.max_rho_iterations) / s_top));
        stage.check(shown, "continuation");
      });
      gn.set_stop_at_cut(false);
      rep.rho_iterations += gr.iterations;  // an abandoned step's too, though the history does not show it
      if (tentative && (gr.cut || !gr.converged)) {
        ++rep.abandoned_steps;
        z = z_start;
        gn.restore(gn_start);
        // The steps of 1 below s_next go in before it, and the loop takes the first of them next
        // (at least one: the step was longer than 1).
        std::vector<double> below{s_cur + 1.0};
        for (double sv = s_cur + 2.0; sv < s_next - 1e-12; sv += 1.0) below.push_back(sv);
        schedule.insert(schedule.begin() + static_cast<std::ptrdiff_t>(k), below.begin(), below.end());
        continue;
      }
      StepInfo step;
      step.s = s_next;
      step.iterations = gr.iterations;
      step.rho_change = gr.rho_change;
      step.converged = gr.converged;
      if (!gr.converged) rep.converged = false;
      const std::pair<int, double> rank = rank_of(z, s_next);
      if (rank >= best_rank) {
        best_rank = rank;
        best_z = z;
        best_s = s_next;
      }
      res.steps.push_back(step);
      ++rep.s_steps;
      rep.rho_change = step.rho_change;
      s_cur = s_next;
      ++k;
    }
    recentre(z);
    recentre(best_z);
    rep.time.assembly += gn.time_assembly();
    gn_counters = gn.counters();
    rep.iterative_iterations += gn.pcg_iterations();
  }
  rep.time.continuation = now() - t_cont;
  rep.s = early ? 0.0 : opt.s;
  if (opt.s > 0 && !early) {
    // The best step is the last one whenever that is valid (ties go to the later step); with a
    // schedule that comes back down from via_s an earlier step may be the best.
    z = best_z;
    rep.s = best_s;
  }

  // s = 0 is scale-free: return the layout with the 3D area.
  if ((rep.s == 0 || early) && gauge.vector) {
    scale_to_3d_area(z);
  }
  stage.check(0.95, "quality");
  glue_scars(tp, mode, z);
  res.uv = z * ls;
  require_finite(res.uv);
  t0 = now();
  rep.quality = evaluate_quality(mesh, tp, res.uv, threads);
  rep.time.quality += now() - t0;
  rep.counters = kkt.counters();
  rep.counters.analyses += gn_counters.analyses;
  rep.counters.factorizations += gn_counters.factorizations;
  rep.counters.solves += gn_counters.solves;
  rep.counters.time_analysis += gn_counters.time_analysis;
  rep.counters.time_factorization += gn_counters.time_factorization;
  rep.counters.time_solve += gn_counters.time_solve;
  rep.time.analysis = rep.counters.time_analysis;
  rep.time.factorization = rep.counters.time_factorization;
  rep.time.solve = rep.counters.time_solve;
  rep.time.total = now() - t_start;
  rep.peak_memory_mb = peak_memory_mb();
  stage.check(1.0, "done");
  return res;
}

}  // namespace

FlattenResult flatten(const FlattenInput& in) {
  FlattenResult res = flatten_attempt(in);
  auto valid = [](const FlattenResult& r) { return r.report.quality.flips == 0 && r.report.quality.boundary_intersections == 0; };
  // A valid layout that the continuation could not carry to the target s (it fell back to a
  // smaller s) is short of what was asked too: the retries below may reach the target.
  auto short_of_target = [&](const FlattenResult& r) { return !valid(r) || r.report.s < in.options.s - 1e-12; };
  // Valid first, then the s reached, then the score.
  auto rank = [&](const FlattenResult& r) { return std::make_tuple(valid(r) ? 1 : 0, valid(r) ? r.report.s : 0.0, r.report.quality.score); };
  auto try_instead = [&](FlattenInput alt_in, auto mark) {
    try {
      FlattenResult alt = flatten_attempt(alt_in);
      if (rank(alt) > rank(res)) {
        mark(alt.report);
        alt.report.time.total += res.report.time.total;
        res = std::move(alt);
      }
    } catch (const Error& e) {
      if (e.code() == Errc::cancelled) throw;
    }
  };
  if (in.options.method != Method::Global || !short_of_target(res)) return res;
  // A domain with flips or a self-overlapping boundary is unusable for meshing; layouts that are
  // valid at the target s never take the paths below, so they cost nothing on them.
  // 1. Needle and zero-area triangles (tiny altitude/base, huge weights) drive most flips: retry with
  //    a stronger floor on beta. Real sample: the bottle thread face, 4 overlaps -> valid, but only
  //    at s = 0 (the unwinding below then reaches s = 1).
  const double floor = 0.05;
  if (in.options.min_beta < floor) {
    FlattenInput alt = in;
    alt.options.min_beta = floor;
    try_instead(alt, [](SolveReport& r) { r.min_beta_raised = true; });
  }
  // 2. The energy below s = 2 lets a layout fold over itself where s = 2 does not (the
  //    altitude term of degree 1 - s grows as a base edge shrinks only for s > 1): climb to s = 2,
  //    then step back down to the target from that valid layout.
  if (in.options.s > 0 && in.options.s < 2.0 && short_of_target(res)) {
    FlattenInput alt = in;
    alt.via_s = 2.0;
    try_instead(alt, [](SolveReport& r) { r.via_s = 2.0; });
  }
  // 3. A face whose low-distortion layout coils over itself (a helical strip: its sides curve one
  //    way for more than a turn) needs its sides straightened: the boundary term, strengthened,
  //    aims gentle turns at a fraction of their 3D value; the least unwinding that gives a valid
  //    layout at the target s wins. The bottle's thread face: valid only at s = 0 before
  //    unwinding (.37), valid at s = 1 with it (.98).
  //    Where weight 10 is not enough, 30 (the two-turn helical strip at s = 2: the area term
  //    coils it again at 10; at 30 it is valid, .928, where it came back at s = 1 before).
  for (double weight : {10.0, 30.0}) {
    if (weight < in.options.boundary_weight) continue;
    for (double unwind : {0.5, 0.25, 0.0}) {
      if (!short_of_target(res)) break;
      FlattenInput alt = in;
      alt.unwind = unwind;
      alt.boundary_weight_override = weight;
      try_instead(alt, [unwind, weight](SolveReport& r) {
        r.unwind = unwind;
        r.unwind_weight = weight;
      });
    }
  }
  return res;
}

}  // namespace wefm
