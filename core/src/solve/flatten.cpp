#include "wefm/core/solve/flatten.hpp"

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <cmath>
#include <utility>
#include <fstream>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <system_error>
#include <tuple>

#include "wefm/core/method/caller_rows.hpp"
#include "wefm/core/sys/clock.hpp"
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

// Measured peaks of whole `wefm flatten` runs, 1M-triangle disk (factor 34.1M entries) and plate
// (26.7M), s = 0, 1, 2: 0.59-0.85 KB per triangle besides the factor; memory_limit_mb counts the
// factor's values (CHOLMOD's xsize from the analysis) plus this much per triangle for the rest.
constexpr double kOtherMbPerTriangle = 0.75e-3;

// Edge lengths squared overflow above about 1e154 and underflow below 1e-154: a mesh whose every
// triangle has zero area may have shape, but not one double precision can measure.
[[noreturn]] void fail_all_degenerate(const TriMesh& mesh) {
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

// An automatic repeated edge's starting mode. An interior slit (both ends shared by its two sides)
// starts glued: started free, the slits that do not want to open leave gaps of zero width, judged
// crossing or not by rounding, and the descent took another path on another BLAS kernel (8-slit
// plate). Not a seam that is the outer loop itself (a full sphere's pole-to-pole seam): there the
// glued start is a closed surface, and the continuation converged less often from it.
EdgeMode automatic_start_mode(const Topology& tp, const RepeatedEdge& r) {
  const auto& outer = tp.loop_uses[static_cast<size_t>(tp.outer_loop)];
  const bool slit = !r.side_a.empty() && r.side_a.front() == r.side_b.front() && r.side_a.back() == r.side_b.back() &&
                    std::find(outer.begin(), outer.end(), r.side_a.front()) == outer.end();
  return slit ? EdgeMode::Scar : EdgeMode::Free;
}

// The continuation's values of s: up to the target in s_step steps, or up to via_s and then back
// down to the target.
std::vector<double> s_schedule(const Options& opt, double s_top) {
  std::vector<double> schedule;
  if (s_top > opt.s) {
    schedule.push_back(s_top);
    const double down = std::min(opt.s_step, 0.5);
    for (double sv = s_top; sv > opt.s + 1e-12;) schedule.push_back(sv = std::max(opt.s, sv - down));
  } else {
    for (double sv = 0; sv < s_top - 1e-12;) schedule.push_back(sv = std::min(s_top, sv + opt.s_step));
  }
  return schedule;
}

// The candidates of one automatic edge's mode, each solved with the other edges' modes fixed.
struct EdgeTrial {
  // Ranked valid first, then by fewer flips and crossings, then by score: with several edges, one
  // edge's choice can remove a crossing while another still makes the layout invalid, and a flat
  // -2 would hide that progress from the descent.
  using Rank = std::tuple<int, std::int64_t, double>;
  // Periodic first: on ties (a developable cylinder is exact both free and periodic) the periodic
  // domain is the one a mesher wants, with matching nodes on the two sides.
  static constexpr std::array<EdgeMode, 4> kOrder = {EdgeMode::Periodic, EdgeMode::Free, EdgeMode::Rotational, EdgeMode::Scar};

  Index e = 0;
  const RepeatedEdge* r = nullptr;
  std::vector<EdgeMode> md;  // the modes with this edge's candidate
  VectorXc z_free;           // the free layout: the free candidate and the rotation estimate's source
  bool free_singular = false;
  std::array<Rank, 4> ranks;
  std::array<double, 4> scores{};
  std::array<std::vector<Complex>, 4> rots;
  std::array<VectorXc, 4> refined;  // the layouts solved with refinement (free always)
  // The unrefined solves, kept so that refining a contender goes on from its solve
  // (PartitionedKKT::refine) instead of repeating it: one factor solve less per contender.
  std::array<PartitionedKKT::Unrefined, 4> unrefined;

  // The best candidate in kOrder (-1: none ranks above nothing, the edge keeps its mode). A
  // constrained mode must beat free clearly: constraints are only worth their rigidity.
  int best() const {
    Rank top{0, std::numeric_limits<std::int64_t>::min(), -std::numeric_limits<double>::infinity()};
    int kb = -1;
    for (size_t k = 0; k < kOrder.size(); ++k) {
      const bool better = std::get<0>(ranks[k]) != std::get<0>(top) || std::get<1>(ranks[k]) != std::get<1>(top)
                              ? ranks[k] > top
                              : std::get<2>(ranks[k]) > std::get<2>(top) + 1e-9;
      if (better) {
        top = ranks[k];
        kb = static_cast<int>(k);
      }
    }
    return kb;
  }
};

// One flatten attempt (METHOD §7) for one set of inputs; flatten() below retries with others. The
// steps run in the order of run(), each reading what the ones before it left in the members.
class Attempt {
 public:
  Attempt(const FlattenInput& in, double t_start)
      : in_(in), mesh_(*in.mesh), tp_(*in.topo), opt_(in.options), stage_(in), t_start_(t_start),
        threads_(std::max(1, opt_.threads)),
        mu_(in.boundary_weight_override > 0 ? in.boundary_weight_override : opt_.boundary_weight),
        other_mb_(kOtherMbPerTriangle * static_cast<double>(mesh_.triangles.size())), kkt_(opt_.backend) {}

  FlattenResult run() {
    rep_.method = opt_.method;
    kkt_.factor().set_threads(opt_.threads);
    kkt_.factor().set_memory_limit(opt_.memory_limit_mb, other_mb_);
    start_analysis();
    compute_coefficients_and_gauges();
    choose_start_modes();
    if (opt_.method == Method::Rollout) return rolled_out();
    assemble_and_analyse();
    first_solve();
    if (!auto_edges_.empty()) choose_automatic_modes();
    for (size_t e = 0; e < tp_.edges.size(); ++e) res_.edge_modes[e] = mode_[e];
    continuation();
    return finish();
  }

 private:
  void start_analysis();
  void compute_coefficients_and_gauges();
  void choose_start_modes();
  FlattenResult rolled_out();
  void assemble_and_analyse();
  void first_solve();
  void choose_automatic_modes();
  bool choose_mode(Index e);
  void try_mode(EdgeTrial& t, size_t k, bool refine);
  void continuation();
  void prepare_gauss_newton(GaussNewton& gn, const SeamSubstitution& sub);
  struct Best {
    VectorXc z;
    std::pair<int, double> rank;
    double s = 0;
  };
  void run_schedule(GaussNewton& gn, double s_top, Best& best);
  FlattenResult finish();

  // The caller's rows, each repeated edge's rows for the modes md and rotations rot, the vector
  // gauge (when given) and the pin.
  std::vector<LinearRow> rows_with(const std::vector<EdgeMode>& md, const std::vector<Complex>& rot, const LinearRow* gauge_row) const {
    std::vector<LinearRow> rows = caller_;
    for (const RepeatedEdge& r : tp_.repeated) {
      auto add = repeated_edge_rows(r, md[static_cast<size_t>(r.edge)], rot[static_cast<size_t>(r.edge)]);
      rows.insert(rows.end(), add.begin(), add.end());
    }
    if (gauge_row) rows.push_back(*gauge_row);
    if (gauge_.translation) rows.push_back(pin_);
    return rows;
  }
  const LinearRow* vector_gauge() const { return gauge_.vector ? &vec_ : nullptr; }

  // Translation is fixed by pinning one gauge use and shifting afterwards (see PartitionedKKT::solve).
  void recentre(VectorXc& zz) const {
    if (!gauge_.translation) return;
    const Complex c = eta_.cast<Complex>().dot(zz) / eta_.sum();
    zz.array() -= c;
  }

  // Scales about the gauge centre so the total UV area equals the 3D area (size-free layouts).
  void scale_to_3d_area(VectorXc& zz) const {
    double uv_area = 0, a3 = 0;
    for (size_t t = 0; t < mesh_.triangles.size(); ++t) {
      const Complex u0 = zz[tp_.corner_use[3 * t]], u1 = zz[tp_.corner_use[3 * t + 1]], u2 = zz[tp_.corner_use[3 * t + 2]];
      uv_area += 0.5 * ((u1 - u0).real() * (u2 - u0).imag() - (u1 - u0).imag() * (u2 - u0).real());
      a3 += coef_.tri_area[t];
    }
    if (uv_area > 0) zz = ((zz.array() - gauge_.center) * std::sqrt(a3 / uv_area) + gauge_.center).matrix();
  }

  // The layout's score; its quality stays in last_quality_.
  double score_of(const VectorXc& zz) {
    const double tq = now();
    last_quality_ = evaluate_quality(mesh_, tp_, zz, threads_);
    rep_.time.quality += now() - tq;
    return last_quality_.score;
  }

  // Gauss-Newton can end in a layout with flips or boundary overlaps where a smaller s gave a valid
  // one (a sphere with a small hole at s = 2): the continuation keeps the valid layout of the
  // largest s reached, and reports that s. Scores are not compared across s: the caller chose s,
  // and on a sphere a valid s = 0.3 layout scores below s = 0 (measured .034 against .039) yet is
  // what was asked for. Only when no step is valid does the best score win.
  std::pair<int, double> rank_of(const VectorXc& zz, double s_of) {
    const double sc = score_of(zz);
    const bool valid = last_quality_.flips == 0 && last_quality_.boundary_intersections == 0 && s_of <= opt_.s + 1e-12;
    return std::make_pair(valid ? 1 : 0, valid ? s_of : sc);
  }

  const FlattenInput& in_;
  const TriMesh& mesh_;
  const Topology& tp_;
  const Options& opt_;
  Stage stage_;
  const double t_start_;
  const int threads_;
  const double mu_;
  const double other_mb_;
  FlattenResult res_;
  SolveReport& rep_ = res_.report;

  // Declared in the order of their use by the early analysis, which reads them from another thread
  // until it is waited for: it goes first on the way out.
  PartitionedKKT kkt_;
  std::pair<Index, Index> split_{0, 0};
  std::vector<Vec3> at_;
  std::unique_ptr<EnergyAssembler> assembler_;
  std::optional<EarlyAnalysis> ahead_;

  int setup_threads_ = 1;
  Coefficients coef_;
  double ls_ = 1.0;
  Eigen::VectorXd eta_;
  std::vector<LinearRow> caller_;
  GaugeChoice gauge_;
  std::vector<EdgeMode> mode_;
  std::vector<Complex> rotation_;
  std::vector<Index> auto_edges_;
  SpMatC B_;
  const SpMatC* Bp_ = nullptr;
  SpMatC K_;
  LinearRow vec_, pin_;
  VectorXc z_;
  Quality last_quality_;
  FactorCounters gn_counters_;
};

// The split uses and the points for the ordering, should minimum degree's fill be poor
// (nested_dissection.hpp): the global method's. K's analysis then runs side by side with the
// coefficients and K's values (early_analysis.hpp; measured at 1M triangles, s = 0: see
// docs/PERFORMANCE.md).
void Attempt::start_analysis() {
  const bool global = opt_.method == Method::Global;
  split_ = global ? far_pair_3d(mesh_, tp_, tp_.outer_loop) : std::pair<Index, Index>{0, 0};
  at_.resize(global ? static_cast<size_t>(tp_.use_count) : 0);
  for (size_t u = 0; u < at_.size(); ++u) at_[u] = mesh_.vertices[static_cast<size_t>(tp_.use_vertex[u])];
  if (global && opt_.residual == Residual::PerHalfEdge && early_analysis_pays(tp_.use_count, threads_)) {
    const double t0 = now();
    const SpMatC b_pattern = boundary_operator_pattern(mesh_, tp_, mu_);
    assembler_ = std::make_unique<EnergyAssembler>(tp_, b_pattern.nonZeros() ? &b_pattern : nullptr, threads_);
    rep_.time.assembly += now() - t0;
    try {
      ahead_.emplace(*assembler_, kkt_, split_.first, split_.second, &at_);
    } catch (const std::system_error&) {
      ahead_.reset();  // no thread to be had: the analysis runs in turn below
    }
  }
}

void Attempt::compute_coefficients_and_gauges() {
  const double t0 = now();
  // While the analysis runs, one thread fewer here: it is the longer of the two (the same bits for
  // any thread count).
  setup_threads_ = ahead_ ? std::max(1, threads_ - 1) : threads_;
  coef_ = compute_coefficients(mesh_, tp_, opt_.curvature_adjust, opt_.min_beta, setup_threads_);
  rep_.time.coefficients = now() - t0;
  rep_.degenerate_triangles = coef_.degenerate_triangles;
  if (coef_.degenerate_triangles == static_cast<Index>(mesh_.triangles.size())) fail_all_degenerate(mesh_);
  ls_ = coef_.length_scale;
  eta_ = Eigen::Map<const Eigen::VectorXd>(coef_.use_area.data(), static_cast<Index>(coef_.use_area.size()));
  caller_ = normalised_caller_rows(in_.constraints, ls_);
  const VectorXc z_ref = planar_projection(mesh_, tp_, ls_);
  gauge_ = choose_gauges(caller_, z_ref);
}

// Modes per repeated edge: forced, or the default, or Auto (decided by choose_automatic_modes).
void Attempt::choose_start_modes() {
  const size_t ne = tp_.edges.size();
  res_.edge_modes.assign(ne, EdgeMode::Free);
  res_.edge_scores.assign(ne, {std::nan(""), std::nan(""), std::nan(""), std::nan(""), std::nan("")});
  mode_.assign(ne, EdgeMode::Free);
  rotation_.assign(ne, Complex(1, 0));
  for (const RepeatedEdge& r : tp_.repeated) {
    auto it = in_.edge_modes.find(r.edge);
    EdgeMode m = it != in_.edge_modes.end() ? it->second : opt_.default_edge_mode;
    if (m == EdgeMode::Auto) {
      auto_edges_.push_back(r.edge);
      m = automatic_start_mode(tp_, r);
    }
    mode_[static_cast<size_t>(r.edge)] = m;
  }
}

FlattenResult Attempt::rolled_out() {
  for (const RepeatedEdge& r : tp_.repeated)
    if (mode_[static_cast<size_t>(r.edge)] != EdgeMode::Free)
      fail(Errc::unsupported, "the roll-out method supports only free repeated edges (edge " + std::to_string(r.edge) + " is not free); use the global method");
  RolloutResult rr = rollout(mesh_, tp_, coef_, caller_, opt_, [&](double f) { stage_.check(f, "rollout"); });
  res_.uv = rr.z * ls_;
  require_finite(res_.uv);
  rep_.iterative_iterations = rr.sweeps;
  rep_.converged = rr.converged;
  rep_.s = opt_.s;  // the roll-out runs at the target s directly (no continuation)
  const double t0 = now();
  rep_.quality = evaluate_quality(mesh_, tp_, res_.uv, threads_);
  rep_.time.quality = now() - t0;
  rep_.time.total = now() - t_start_;
  rep_.peak_memory_mb = peak_memory_mb();
  return std::move(res_);
}

// The boundary operator B and K straight into its pattern, without the surface operator A
// (K = A^H A + B^H B: A would cost nine entries per triangle and two passes); K analysed (unless
// the early analysis did) and factorised.
void Attempt::assemble_and_analyse() {
  stage_.check(0.05, "assembly");
  const double t0 = now();
  B_ = assemble_boundary_operator(mesh_, tp_, coef_, mu_, in_.unwind);
  Bp_ = B_.rows() ? &B_ : nullptr;
  const std::vector<double> rho;  // empty: s = 0
  if (ahead_) ahead_->copied();
  const bool foreseen = assembler_ && assembler_->set_boundary(Bp_);  // B's pattern is the one analysed
  const bool analysed = ahead_ && foreseen;
  K_ = foreseen ? assembler_->assemble(compute_weights(tp_, coef_, opt_.k, setup_threads_), compute_sigma(coef_, rho, 0.0, setup_threads_), setup_threads_)
                : assemble_energy(tp_, coef_, compute_sigma(coef_, rho, 0.0, threads_), opt_.k, opt_.residual, Bp_, threads_);
  assembler_.reset();
  rep_.time.assembly += now() - t0;
  stage_.check(0.1, "factorise");
  if (ahead_) {
    const double tw = now();
    ahead_->wait();
    // The analysis overlapped the coefficients and assembly: the solve's timers count only the
    // time it waited for it, so that they still add up to its wall time.
    kkt_.counters().time_analysis = now() - tw;
  }
  // Analysed already, unless B's pattern was not the one foreseen (then it is analysed here).
  kkt_.set_matrix(K_, split_.first, split_.second, analysed ? nullptr : &at_);
  ahead_.reset();
  std::vector<Vec3>().swap(at_);
}

// The conformal solve (s = 0) with the two-step gauge.
void Attempt::first_solve() {
  const auto seg = longest_loop_segment(tp_, mesh_, tp_.outer_loop);
  pin_.terms = {{seg.first, 1.0}};
  pin_.rhs = 0.0;
  if (gauge_.vector) {
    const double L = (mesh_.vertices[static_cast<size_t>(tp_.use_vertex[static_cast<size_t>(seg.second)])] -
                      mesh_.vertices[static_cast<size_t>(tp_.use_vertex[static_cast<size_t>(seg.first)])]).norm() / ls_;
    vec_.terms = {{seg.second, 1.0}, {seg.first, -1.0}};
    vec_.rhs = L;
  }
  stage_.check(0.2, "solve");
  // With a vector gauge this first layout only locates the far pair below: not refined.
  z_ = kkt_.solve(rows_with(mode_, rotation_, vector_gauge()), nullptr, !gauge_.vector);
  recentre(z_);
  if (gauge_.vector) {
    // Fixing one short facet edge lets its local error tilt the whole layout; fix the vector
    // between two far-apart boundary uses instead. Same factorisation.
    const auto fp = far_pair(tp_, z_, tp_.outer_loop);
    if (fp.first != fp.second) {
      vec_.terms = {{fp.second, 1.0}, {fp.first, -1.0}};
      vec_.rhs = z_[fp.second] - z_[fp.first];
      pin_.terms = {{fp.first, 1.0}};
      pin_.rhs = z_[fp.first];
    }
    z_ = kkt_.solve(rows_with(mode_, rotation_, &vec_), nullptr);  // refined (without a far pair: the first gauge again)
    recentre(z_);
  }
}

// Repeated edges: each automatic edge's mode chosen by score (METHOD §7 step 2), by coordinate
// descent over the edges: each tries every mode with the others fixed; two passes at most. Cost:
// 4 x edges x passes small dense solves, one factorisation in all.
void Attempt::choose_automatic_modes() {
  stage_.check(0.3, "repeated edges");
  std::vector<Index> seam_uses;
  for (const RepeatedEdge& r : tp_.repeated) {
    seam_uses.insert(seam_uses.end(), r.side_a.begin(), r.side_a.end());
    seam_uses.insert(seam_uses.end(), r.side_b.begin(), r.side_b.end());
  }
  kkt_.prepare(seam_uses, nullptr);
  size_t last_changed = auto_edges_.size();  // the edge whose mode changed last
  for (int pass = 0; pass < 2; ++pass) {
    bool changed = false;
    for (size_t i = 0; i < auto_edges_.size(); ++i) {
      // Back at the edge that changed last: every other edge has been tried since, with the modes
      // as they are now, and kept its mode, so each would choose as before (a face with one seam
      // paid for a second pass of identical solves).
      if (pass > 0 && i == last_changed) return;
      if (choose_mode(auto_edges_[i])) {
        changed = true;
        last_changed = i;
      }
    }
    if (!changed) return;
  }
}

// Edge e's mode, the others fixed; true when it changed. The layout becomes the chosen candidate's.
bool Attempt::choose_mode(Index e) {
  EdgeTrial t;
  t.e = e;
  t.r = &tp_.repeated[static_cast<size_t>(tp_.edge_repeated[static_cast<size_t>(e)])];
  t.md = mode_;
  t.md[static_cast<size_t>(e)] = EdgeMode::Free;
  // The free layout, solved once: the free candidate, and the rotation estimate of the rotational
  // one (each solve costs a few solves with the factor).
  t.z_free = z_;
  try {
    t.z_free = kkt_.solve(rows_with(t.md, rotation_, vector_gauge()), nullptr);
  } catch (const Error& err) {
    if (err.code() != Errc::singular) throw;
    t.free_singular = true;
  }
  // Every candidate but free (refined above) is solved without refinement first, and again with it
  // only where it could matter: the winner and the valid candidates within kRefineMargin of its
  // score, or every candidate when none is valid. Refinement moves a score by 5e-10 at most
  // (1M-triangle tube), far inside the margin, so the choice is the one refined candidates give;
  // each refinement costs two solves with the factor.
  const auto& kOrder = EdgeTrial::kOrder;
  for (size_t k = 0; k < kOrder.size(); ++k) try_mode(t, k, false);
  const int first = t.best();
  const bool valid_best = first >= 0 && std::get<0>(t.ranks[static_cast<size_t>(first)]) == 1;
  for (size_t k = 0; k < kOrder.size(); ++k) {
    if (kOrder[k] == EdgeMode::Free) continue;
    const bool contender = !valid_best || (std::get<0>(t.ranks[k]) == 1 && t.scores[k] >= t.scores[static_cast<size_t>(first)] - kRefineMargin);
    if (contender) try_mode(t, k, true);
  }
  const int kb = t.best();
  for (size_t k = 0; k < kOrder.size(); ++k) {
    const double sc = t.scores[k];
    res_.edge_scores[static_cast<size_t>(e)][static_cast<size_t>(kOrder[k])] = std::isfinite(sc) ? sc : -3.0;
  }
  EdgeMode chosen = mode_[static_cast<size_t>(e)];
  VectorXc z_chosen = z_;
  if (kb >= 0) {
    const size_t k = static_cast<size_t>(kb);
    // A contender that refinement made invalid can leave the win to a candidate judged unrefined.
    if (t.refined[k].size() == 0) try_mode(t, k, true);
    chosen = kOrder[k];
    z_chosen = std::move(t.refined[k]);
    if (chosen == EdgeMode::Rotational) rotation_[static_cast<size_t>(e)] = t.rots[k][static_cast<size_t>(e)];
  }
  const bool changed = chosen != mode_[static_cast<size_t>(e)];
  mode_[static_cast<size_t>(e)] = chosen;
  z_ = std::move(z_chosen);
  return changed;
}

// Candidate k of the trial: solved (with refinement or not), glued, scored and ranked.
void Attempt::try_mode(EdgeTrial& t, size_t k, bool refine) {
  const EdgeMode cand = EdgeTrial::kOrder[k];
  t.md[static_cast<size_t>(t.e)] = cand;
  t.rots[k] = rotation_;
  if (cand == EdgeMode::Rotational) t.rots[k][static_cast<size_t>(t.e)] = estimate_rotation(*t.r, t.z_free);
  double sc;
  EdgeTrial::Rank rank;
  VectorXc zc;
  try {
    if (cand == EdgeMode::Free && t.free_singular) fail(Errc::singular, "free candidate");
    if (cand == EdgeMode::Free) {
      zc = t.z_free;
    } else {
      const std::vector<LinearRow> rows = rows_with(t.md, t.rots[k], vector_gauge());
      if (refine) {
        zc = t.unrefined[k].z.size() > 0 ? kkt_.refine(rows, nullptr, std::move(t.unrefined[k])) : kkt_.solve(rows, nullptr);
        t.unrefined[k] = PartitionedKKT::Unrefined{};
      } else {
        t.unrefined[k] = kkt_.solve_unrefined(rows, nullptr);
        zc = t.unrefined[k].z;
      }
    }
    recentre(zc);
    glue_scars(tp_, t.md, zc);
    sc = score_of(zc);
    const std::int64_t bad = last_quality_.flips + last_quality_.boundary_intersections;
    rank = EdgeTrial::Rank{bad == 0 ? 1 : 0, -bad, sc};
    // Sides that land on each other (a flat ring: periodic with a zero shift, rotational by zero,
    // free) are the scar, judged by rounding as touching or not: the scar candidate glues them
    // exactly, and it alone may take that layout.
    if (cand != EdgeMode::Scar && sides_coincide(*t.r, zc)) rank = EdgeTrial::Rank{0, std::numeric_limits<std::int64_t>::min(), sc};
  } catch (const Error& err) {
    if (err.code() != Errc::singular) throw;
    sc = -std::numeric_limits<double>::infinity();
    rank = EdgeTrial::Rank{0, std::numeric_limits<std::int64_t>::min(), sc};
  }
  if (cand == EdgeMode::Free) t.z_free = zc;
  t.ranks[k] = rank;
  t.scores[k] = sc;
  if (refine || cand == EdgeMode::Free) t.refined[k] = std::move(zc);
}

// Continuation in s from the conformal layout to the target s (METHOD §7 step 3), unless the
// conformal layout already scores above Options::score_threshold.
void Attempt::continuation() {
  const bool early = opt_.s > 0 && opt_.score_threshold <= 1.0 && score_of(z_) >= opt_.score_threshold;
  const double t_cont = now();
  rep_.s = early ? 0.0 : opt_.s;
  if (opt_.s > 0 && !early) {
    Best best{z_, rank_of(z_, 0.0), 0.0};
    // For s > 0 the energy fixes the size: start from the layout with the 3D area.
    if (gauge_.vector) scale_to_3d_area(z_);
    const SeamSubstitution sub = substitute_seams(tp_, mode_, rotation_);
    std::vector<LinearRow> keep;
    for (const LinearRow& r : caller_) keep.push_back(reduce_row(sub, r));
    keep.insert(keep.end(), sub.leftover.begin(), sub.leftover.end());
    // The s = 0 factor becomes the continuation's preconditioner, refactorised in place; with
    // substituted seams the continuation factorises its own pattern: do not hold two factors.
    // The caches (a copy of K among them) go first, before the continuation allocates.
    kkt_.release_caches();
    GaussNewton gn(tp_, coef_, Bp_, opt_.k, opt_.residual, K_, sub, keep, opt_.backend, opt_.min_beta, threads_);  // takes K over (K is not needed after)
    prepare_gauss_newton(gn, sub);
    run_schedule(gn, in_.via_s > opt_.s ? in_.via_s : opt_.s, best);
    // The best step is the last one whenever that is valid (ties go to the later step); with a
    // schedule that comes back down from via_s an earlier step may be the best.
    recentre(best.z);
    z_ = std::move(best.z);
    rep_.s = best.s;
    rep_.time.assembly += gn.time_assembly();
    gn_counters_ = gn.counters();
    rep_.iterative_iterations += gn.pcg_iterations();
  }
  rep_.time.continuation = now() - t_cont;
  // s = 0 is scale-free: return the layout with the 3D area.
  if ((rep_.s == 0 || early) && gauge_.vector) scale_to_3d_area(z_);
}

// The continuation's steps along s_schedule, each a Gauss-Newton run from the last one's layout;
// `best` keeps the best of them by rank_of.
void Attempt::run_schedule(GaussNewton& gn, double s_top, Best& best) {
  std::vector<double> schedule = s_schedule(opt_, s_top);
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
    const bool tentative = s_top == opt_.s && s_next - s_cur > 1.0 + 1e-12;
    const VectorXc z_start = tentative ? z_ : VectorXc();
    const GaussNewton::State gn_start = gn.state();
    // A step on the way up only places the next one's start: it stops at kWayUpTolerance times
    // the tolerance. Measured at s = 2 on the real sample and the synthetic faces: the same scores
    // to 1e-4 (bottle .99330 -> .99338, helix .928282 -> .928296), Gauss-Newton iterations fewer
    // on 9 of 19 faces (revolved sphere 53 -> 49, MAT 21 -> 18), the 1M disk 7 -> 6. A single
    // predictor iteration instead cost the bottle and the sphere with a small hole (SOLVER.md).
    const bool way_up = s_top == opt_.s && k + 1 < schedule.size();
    const double tol = way_up ? kWayUpTolerance * opt_.rho_tolerance : opt_.rho_tolerance;
    gn.set_stop_at_cut(tentative);
    const GaussNewtonReport gr = gn.run(z_, s_next, tol, opt_.max_rho_iterations, gauge_.vector && s_next >= 1.0, [&](int it) {
      shown = std::max(shown, 0.4 + 0.5 * std::min(1.0, (s_cur + (s_next - s_cur) * it / opt_.max_rho_iterations) / s_top));
      stage_.check(shown, "continuation");
    });
    gn.set_stop_at_cut(false);
    rep_.rho_iterations += gr.iterations;  // an abandoned step's too, though the history does not show it
    if (tentative && (gr.cut || !gr.converged)) {
      ++rep_.abandoned_steps;
      z_ = z_start;
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
    if (!gr.converged) rep_.converged = false;
    const std::pair<int, double> rank = rank_of(z_, s_next);
    if (rank >= best.rank) {
      best.rank = rank;
      best.z = z_;
      best.s = s_next;
    }
    res_.steps.push_back(step);
    ++rep_.s_steps;
    rep_.rho_change = step.rho_change;
    s_cur = s_next;
    ++k;
  }
}

void Attempt::prepare_gauss_newton(GaussNewton& gn, const SeamSubstitution& sub) {
  gn.own_factor().set_threads(opt_.threads);
  gn.set_threads(opt_.threads);
  gn.own_factor().set_memory_limit(opt_.memory_limit_mb, other_mb_);
  if (!gn.share_factor(kkt_.factor(), kkt_.split_use(0), kkt_.split_use(1))) {
    kkt_.release();
    // Its own factor orders its own pattern: points for the ordering, as for K_PP (without them a
    // rotational seam's pattern can fall to METIS, whose analysis costs far more). A seam's shift
    // sits at the mean of the uses it moves.
    std::vector<Vec3> points(static_cast<size_t>(sub.reduced), Vec3::Zero());
    for (Index c = 0; c < sub.reduced; ++c) {
      int k = 0;
      for (SpMatC::InnerIterator it(sub.P, c); it; ++it, ++k)
        points[static_cast<size_t>(c)] += mesh_.vertices[static_cast<size_t>(tp_.use_vertex[static_cast<size_t>(it.row())])];
      if (k > 1) points[static_cast<size_t>(c)] /= k;
    }
    gn.own_factor().set_ordering_points(std::move(points));
  }
  if (gauge_.vector) gn.set_gauge_row(reduce_row(sub, vec_));
  gn.set_scale_center(gauge_.center);
}

// Scars glued, the layout in the input's units, its quality and the report's totals.
FlattenResult Attempt::finish() {
  stage_.check(0.95, "quality");
  glue_scars(tp_, mode_, z_);
  res_.uv = z_ * ls_;
  require_finite(res_.uv);
  const double t0 = now();
  rep_.quality = evaluate_quality(mesh_, tp_, res_.uv, threads_);
  rep_.time.quality += now() - t0;
  rep_.counters = kkt_.counters();
  rep_.counters.analyses += gn_counters_.analyses;
  rep_.counters.factorizations += gn_counters_.factorizations;
  rep_.counters.solves += gn_counters_.solves;
  rep_.counters.time_analysis += gn_counters_.time_analysis;
  rep_.counters.time_factorization += gn_counters_.time_factorization;
  rep_.counters.time_solve += gn_counters_.time_solve;
  rep_.time.analysis = rep_.counters.time_analysis;
  rep_.time.factorization = rep_.counters.time_factorization;
  rep_.time.solve = rep_.counters.time_solve;
  rep_.time.total = now() - t_start_;
  rep_.peak_memory_mb = peak_memory_mb();
  stage_.check(1.0, "done");
  return std::move(res_);
}

FlattenResult flatten_attempt(const FlattenInput& in) {
  const double t_start = now();
  validate_options(in.options);
  // OpenBLAS's pool is the host's unless it opted in to a thread count (wefm.h, "Process policy").
  // Either way the layout does not depend on opt.threads: OpenBLAS splits a call by its own thread
  // count and the call's sizes, never by which or how many threads call it, and every BLAS call
  // of a solve has the same sizes for any opt.threads.
  apply_solve_blas_threads();
  Stage(in).check(0.0, "coefficients");
  return Attempt(in, t_start).run();
}
}  // namespace

namespace {

bool valid(const FlattenResult& r) { return r.report.quality.flips == 0 && r.report.quality.boundary_intersections == 0; }

// A valid layout that the continuation could not carry to the target s (it fell back to a smaller
// s) is short of what was asked too: the retries may reach the target.
bool short_of_target(const FlattenResult& r, double s) { return !valid(r) || r.report.s < s - 1e-12; }

// Valid first, then the s reached, then the score.
std::tuple<int, double, double> rank(const FlattenResult& r) {
  return std::make_tuple(valid(r) ? 1 : 0, valid(r) ? r.report.s : 0.0, r.report.quality.score);
}

// One retry: how it changes the attempt's input, and the mark it leaves on the report when it wins.
struct Retry {
  std::function<void(FlattenInput&)> change;
  std::function<void(SolveReport&)> mark;
};

// The retry policy of the global method: the strategies flatten() tries in turn while the best
// layout so far is short of the target. A domain with flips or a self-overlapping boundary is
// unusable for meshing; layouts that are valid at the target s never take them, so they cost
// nothing there.
std::vector<Retry> retry_sequence(const Options& opt) {
  std::vector<Retry> seq;
  // 1. Needle and zero-area triangles (tiny altitude/base, huge weights) drive most flips: retry
  //    with a stronger floor on beta. Real sample: the bottle thread face, 4 overlaps -> valid, but
  //    only at s = 0 (the unwinding below then reaches s = 1).
  const double floor = 0.05;
  if (opt.min_beta < floor)
    seq.push_back({[floor](FlattenInput& alt) { alt.options.min_beta = floor; }, [](SolveReport& r) { r.min_beta_raised = true; }});
  // 2. The energy below s = 2 lets a layout fold over itself where s = 2 does not (the altitude
  //    term of degree 1 - s grows as a base edge shrinks only for s > 1): climb to s = 2, then step
  //    back down to the target from that valid layout.
  if (opt.s > 0 && opt.s < 2.0)
    seq.push_back({[](FlattenInput& alt) { alt.via_s = 2.0; }, [](SolveReport& r) { r.via_s = 2.0; }});
  // 3. A face whose low-distortion layout coils over itself (a helical strip: its sides curve one
  //    way for more than a turn) needs its sides straightened: the boundary term, strengthened,
  //    aims gentle turns at a fraction of their 3D value; the least unwinding that gives a valid
  //    layout at the target s wins. The bottle's thread face: valid only at s = 0 before
  //    unwinding (.37), valid at s = 1 with it (.98).
  //    Where weight 10 is not enough, 30 (the two-turn helical strip at s = 2: the area term
  //    coils it again at 10; at 30 it is valid, .928, where it came back at s = 1 before).
  for (double weight : {10.0, 30.0}) {
    if (weight < opt.boundary_weight) continue;
    for (double unwind : {0.5, 0.25, 0.0})
      seq.push_back({[unwind, weight](FlattenInput& alt) {
                       alt.unwind = unwind;
                       alt.boundary_weight_override = weight;
                     },
                     [unwind, weight](SolveReport& r) {
                       r.unwind = unwind;
                       r.unwind_weight = weight;
                     }});
  }
  return seq;
}

}  // namespace

FlattenResult flatten(const FlattenInput& in) {
  FlattenResult res = flatten_attempt(in);
  if (in.options.method != Method::Global) return res;
  for (const Retry& retry : retry_sequence(in.options)) {
    if (!short_of_target(res, in.options.s)) break;
    FlattenInput alt_in = in;
    retry.change(alt_in);
    try {
      FlattenResult alt = flatten_attempt(alt_in);
      if (rank(alt) > rank(res)) {
        retry.mark(alt.report);
        alt.report.time.total += res.report.time.total;
        res = std::move(alt);
      }
    } catch (const Error& e) {
      if (e.code() == Errc::cancelled) throw;
    }
  }
  return res;
}

}  // namespace wefm
