#include "wefm/core/solve/face.hpp"

#include <cmath>
#include <string>

#include "wefm/core/solve/annulus_choice.hpp"
#include "wefm/core/sys/clock.hpp"
#include "wefm/core/sys/error.hpp"

namespace wefm {

void Face::require_mesh(const char* what) const {
  if (!has_mesh_) fail(Errc::invalid_state, std::string(what) + " needs a mesh: set the face's mesh first", Remedy::set_mesh);
}

void Face::set_mesh(TriMesh mesh) {
  HalfEdges he = validate_mesh(mesh);
  mesh_ = std::move(mesh);
  half_edges_ = std::move(he);
  has_mesh_ = true;
  spec_ = TopologySpec{};
  topo_.reset();
  rows_.clear();
  result_.reset();
  edge_nodes_.clear();
}

void Face::set_options(const Options& o) {
  validate_options(o);
  // Switching auto_cut on a face it cuts (or would cut: an annulus) changes the topology, and
  // with it the use ids: that clears constraints and the result like any topology change.
  const bool cut_changes = topo_ && o.auto_cut != options_.auto_cut && spec_.loops.empty() && spec_.seams.empty() &&
                           (!cut_.seams.empty() || topo_->loops.size() == 2);
  options_ = o;
  if (cut_changes) topology_changed();
}

void Face::topology_changed() {
  topo_.reset();
  edge_nodes_.clear();
  rows_.clear();
  result_.reset();
}

void Face::clear_topology() {
  spec_ = TopologySpec{};
  topology_changed();
}

Index Face::add_edge(std::vector<Index> chain) {
  require_mesh("adding an edge");
  if (chain.empty()) fail(Errc::invalid_argument, "an edge needs at least one vertex");
  for (size_t j = 0; j < chain.size(); ++j)
    if (chain[j] < 0 || static_cast<size_t>(chain[j]) >= mesh_.vertices.size())
      fail(Errc::out_of_range, "edge vertex " + std::to_string(chain[j]) + " at position " + std::to_string(j) + " is out of range [0, " + std::to_string(mesh_.vertices.size()) + ")");
  spec_.edges.push_back(std::move(chain));
  topology_changed();
  return static_cast<Index>(spec_.edges.size() - 1);
}

Index Face::add_loop(std::vector<EdgeUse> loop) {
  require_mesh("adding a loop");
  if (loop.empty()) fail(Errc::invalid_argument, "a loop needs at least one edge use");
  for (size_t j = 0; j < loop.size(); ++j)
    if (loop[j].edge < 0 || static_cast<size_t>(loop[j].edge) >= spec_.edges.size())
      fail(Errc::out_of_range, "loop edge " + std::to_string(loop[j].edge) + " at position " + std::to_string(j) + " does not exist (" + std::to_string(spec_.edges.size()) + " edges added)");
  spec_.loops.push_back(std::move(loop));
  topology_changed();
  return static_cast<Index>(spec_.loops.size() - 1);
}

void Face::set_outer_loop(Index loop) {
  require_mesh("setting the outer loop");
  if (loop < -1) fail(Errc::out_of_range, "outer loop " + std::to_string(loop) + " is negative (use -1 for automatic)");
  spec_.outer_loop = loop;
  topology_changed();
}

void Face::add_seams(const std::vector<std::pair<Index, Index>>& seams) {
  require_mesh("adding seams");
  const Index nv = static_cast<Index>(mesh_.vertices.size());
  for (size_t j = 0; j < seams.size(); ++j)
    if (seams[j].first < 0 || seams[j].second < 0 || seams[j].first >= nv || seams[j].second >= nv)
      fail(Errc::out_of_range, "seam " + std::to_string(j) + " (" + std::to_string(seams[j].first) + ", " + std::to_string(seams[j].second) + ") has a vertex index out of range [0, " + std::to_string(nv) + ")");
  spec_.seams.insert(spec_.seams.end(), seams.begin(), seams.end());
  topology_changed();
}

void Face::set_edge_mode(Index edge, EdgeMode mode) {
  require_mesh("setting an edge mode");
  const int m = static_cast<int>(mode);
  if (m < 0 || m > 4) fail(Errc::invalid_argument, "edge mode " + std::to_string(m) + " is not an edge mode (0 auto, 1 free, 2 periodic, 3 scar, 4 rotational)");
  const Index ne = static_cast<Index>(topology().edges.size());
  if (edge < 0 || edge >= ne) fail(Errc::out_of_range, "edge " + std::to_string(edge) + " does not exist (" + std::to_string(ne) + " edges)");
  spec_.edge_modes[edge] = mode;
  result_.reset();
}

bool Face::auto_cut_applies() const { return options_.auto_cut && spec_.loops.empty() && spec_.seams.empty(); }

const Topology& Face::topology() {
  require_mesh("the topology");
  if (!topo_) {
    cut_ = AutoCut{};
    if (auto_cut_applies()) cut_ = compute_auto_cut(mesh_);
    if (cut_.seams.empty()) {
      topo_ = build_topology(mesh_, spec_, &half_edges_);
    } else {
      // The cut annulus or sphere has one loop: a boundary-cycle index given for the uncut face
      // does not apply to it.
      TopologySpec cut_spec = spec_;
      cut_spec.seams = cut_.seams;
      cut_spec.outer_loop = -1;
      topo_ = build_topology(mesh_, cut_spec, &half_edges_);
    }
  }
  return *topo_;
}

void Face::set_edge_nodes(Index edge, std::vector<Vec3> nodes) {
  const Topology& tp = topology();
  const Index ne = static_cast<Index>(tp.edges.size());
  if (edge < 0 || edge >= ne) fail(Errc::out_of_range, "edge " + std::to_string(edge) + " does not exist (" + std::to_string(ne) + " edges)");
  if (nodes.size() < 2) fail(Errc::invalid_argument, "edge nodes must include both end vertices (got " + std::to_string(nodes.size()) + " nodes)");
  // Only the size of the face: the full statistics would rebuild its topology once per edge.
  const double tol = 1e-6 * bbox_diagonal(mesh_);
  const auto& ch = tp.edges[static_cast<size_t>(edge)];
  for (size_t j = 0; j < nodes.size(); ++j) {
    const Vec3& p = nodes[j];
    if (!p.allFinite()) fail(Errc::invalid_argument, "edge node " + std::to_string(j) + " is not finite");
    double best = ch.size() == 1 ? (mesh_.vertices[static_cast<size_t>(ch[0])] - p).norm() : 1e300;
    for (size_t k = 0; k + 1 < ch.size(); ++k) {
      const Vec3 a = mesh_.vertices[static_cast<size_t>(ch[k])], b = mesh_.vertices[static_cast<size_t>(ch[k + 1])];
      const double l2 = (b - a).squaredNorm();
      const double t = l2 > 0 ? std::min(1.0, std::max(0.0, (p - a).dot(b - a) / l2)) : 0.0;
      best = std::min(best, (a + t * (b - a) - p).norm());
    }
    if (best > tol)
      fail(Errc::invalid_argument, "edge node " + std::to_string(j) + " lies " + std::to_string(best) + " away from edge " + std::to_string(edge) + "'s facet chain");
  }
  edge_nodes_[edge] = std::move(nodes);
}

Index Face::add_constraint(LinearRow row) {
  const Topology& tp = topology();
  if (row.terms.empty()) fail(Errc::invalid_constraint, "a constraint needs at least one term");
  for (size_t j = 0; j < row.terms.size(); ++j) {
    const auto& [u, g] = row.terms[j];
    if (u < 0 || u >= tp.use_count)
      fail(Errc::invalid_constraint, "constraint term " + std::to_string(j) + " names use " + std::to_string(u) + ", which does not exist (" + std::to_string(tp.use_count) + " uses)");
    if (!std::isfinite(g.real()) || !std::isfinite(g.imag())) fail(Errc::invalid_constraint, "constraint term " + std::to_string(j) + " has a non-finite coefficient");
  }
  if (!std::isfinite(row.rhs.real()) || !std::isfinite(row.rhs.imag())) fail(Errc::invalid_constraint, "constraint right-hand side is not finite");
  rows_.push_back(std::move(row));
  result_.reset();
  return static_cast<Index>(rows_.size() - 1);
}

void Face::clear_constraints() {
  rows_.clear();
  result_.reset();
}

void Face::solve(const ProgressFn& progress, const std::atomic<bool>* cancel) {
  require_mesh("solving");
  const double t0 = now();
  if (progress && !progress(0.0, "topology")) fail(Errc::cancelled, "cancelled by the progress callback before the topology was built");
  const Topology& tp = topology();
  const double t_topo = now() - t0;
  FlattenInput in;
  in.mesh = &mesh_;
  in.topo = &tp;
  in.options = options_;
  in.constraints = rows_;
  in.edge_modes = spec_.edge_modes;
  in.progress = progress;
  in.cancel = cancel;
  FlattenResult r = flatten(in);
  if (cut_.kind != AutoCutKind::None) {
    r.report.auto_cut = true;
    r.report.auto_cut_edges = static_cast<Index>(cut_.seams.size());
    r.report.auto_cut_length = cut_.length;
  }
  if (cut_.kind == AutoCutKind::Annulus) keep_uncut_if_better(mesh_, spec_, tp, in, r);
  r.report.time.topology = t_topo;
  r.report.time.total += t_topo;
  result_ = std::move(r);
  if (!result_->report.converged && options_.method == Method::Rollout) {
    const int sweeps = result_->report.iterative_iterations;
    fail(Errc::not_converged, "the roll-out's sweeps " +
                                  (sweeps < options_.max_rollout_sweeps ? "diverged to overflow after " + std::to_string(sweeps) + " sweeps"
                                                                        : "did not settle within max_rollout_sweeps (" + std::to_string(sweeps) + ")") +
                                  "; the layout after the smallest sweep move is available");
  }
  if (!result_->report.converged) {
    std::string where = "a continuation step";
    if (!result_->steps.empty()) {
      const StepInfo* bad = &result_->steps.back();
      for (const StepInfo& st : result_->steps)
        if (!st.converged) {
          bad = &st;
          break;
        }
      where = "the step to s = " + std::to_string(bad->s) + " (" + std::to_string(bad->iterations) + " iterations, relative rho change " +
              std::to_string(bad->rho_change) + ")";
    }
    fail(Errc::not_converged, "the continuation did not converge within max_rho_iterations at " + where +
                                  "; the best layout reached (s = " + std::to_string(result_->report.s) + ") is available");
  }
}

const FlattenResult& Face::result() const {
  if (!result_) fail(Errc::invalid_state, "no result: solve the face first (or the last change cleared it)", Remedy::solve_first);
  return *result_;
}

}  // namespace wefm
