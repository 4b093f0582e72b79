#include "wefm/core/method/rollout.hpp"

#include <cmath>
#include <limits>
#include <queue>
#include <string>
#include <utility>
#include <vector>

#include "wefm/core/sys/error.hpp"
#include "wefm/core/method/gauge.hpp"

namespace wefm {

namespace {

// A table of items per use (compressed rows): the items of use u are items[start[u] .. start[u + 1]).
struct PerUse {
  std::vector<Index> start, items;
};

// Each half-edge h filed under the use key(h), in half-edge order.
template <class Key>
PerUse file_half_edges(Index n, size_t nh, Key&& key) {
  PerUse t;
  t.start.assign(static_cast<size_t>(n) + 1, 0);
  t.items.resize(nh);
  for (size_t h = 0; h < nh; ++h) ++t.start[static_cast<size_t>(key(h)) + 1];
  for (size_t i = 1; i < t.start.size(); ++i) t.start[i] += t.start[i - 1];
  std::vector<Index> fill(t.start.begin(), t.start.end() - 1);
  for (size_t h = 0; h < nh; ++h) t.items[static_cast<size_t>(fill[static_cast<size_t>(key(h))]++)] = static_cast<Index>(h);
  return t;
}

// The roll-out's state: the layout, which uses are placed, and the growth front ordered by how
// much of each unplaced use's ring is placed.
class Rollout {
 public:
  Rollout(const Topology& tp, const Coefficients& c, const Options& opt)
      : tp_(tp), c_(c), opt_(opt), n_(tp.use_count), nh_(c.alpha.size()) {
    rr_.z = VectorXc::Zero(n_);
    placed_.assign(static_cast<size_t>(n_), 0);
    fixed_.assign(static_cast<size_t>(n_), 0);
    // Half-edges opposite each use (the use's predictions), and the corners of each use.
    opposite_ = file_half_edges(n_, nh_, [&](size_t h) { return opp_use(h); });
    corners_ = file_half_edges(n_, nh_, [&](size_t h) { return tp_.corner_use[h]; });
  }

  void place_pins(const std::vector<LinearRow>& pins);
  void seed(const TriMesh& mesh);
  void grow(const std::function<void(double)>& check);
  void sweep(const std::function<void(double)>& check);
  void centre();
  RolloutResult result() { return std::move(rr_); }

 private:
  Index opp_use(size_t h) const { return tp_.corner_use[static_cast<size_t>(HalfEdges::prev(static_cast<Index>(h)))]; }
  Index u1(size_t h) const { return tp_.corner_use[h]; }
  Index u2(size_t h) const { return tp_.corner_use[static_cast<size_t>(HalfEdges::next(static_cast<Index>(h)))]; }
  bool predict(Index i, bool only_placed, Complex& out) const;
  void on_placed(Index j);

  const Topology& tp_;
  const Coefficients& c_;
  const Options& opt_;
  const Index n_;
  const size_t nh_;
  RolloutResult rr_;
  std::vector<char> placed_, fixed_;
  PerUse opposite_, corners_;
  // Ring ratio: 3D length of placed ring edges over the ring's perimeter, largest first.
  std::vector<double> ring_placed_, ring_total_;
  std::priority_queue<std::pair<double, Index>> pq_;
};

void Rollout::place_pins(const std::vector<LinearRow>& pins) {
  for (size_t r = 0; r < pins.size(); ++r) {
    if (pins[r].terms.size() != 1) fail(Errc::unsupported, "the roll-out method supports pins only; constraint " + std::to_string(r) + " has " + std::to_string(pins[r].terms.size()) + " terms");
    const auto [u, g] = pins[r].terms[0];
    rr_.z[u] = pins[r].rhs / g;
    placed_[static_cast<size_t>(u)] = fixed_[static_cast<size_t>(u)] = 1;
  }
}

// Use i at the 1/beta-weighted average of its predictions (from placed half-edges only, or all);
// false when it has none.
bool Rollout::predict(Index i, bool only_placed, Complex& out) const {
  const double s = opt_.s;
  Complex acc{0, 0};
  double wsum = 0;
  for (Index k = opposite_.start[static_cast<size_t>(i)]; k < opposite_.start[static_cast<size_t>(i) + 1]; ++k) {
    const size_t h = static_cast<size_t>(opposite_.items[static_cast<size_t>(k)]);
    const Index a = u1(h), b = u2(h);
    if (only_placed && (!placed_[static_cast<size_t>(a)] || !placed_[static_cast<size_t>(b)])) continue;
    const Complex e = rr_.z[b] - rr_.z[a];
    const double d = std::abs(e);
    const double rho = d > 0 && c_.length[h] > 0 ? c_.length[h] / d : 1.0;
    const Complex sigma(c_.alpha[h], c_.beta[h] * std::pow(rho, s));
    const double w = 1.0 / c_.beta[h];
    acc += w * (rr_.z[a] + sigma * e);
    wsum += w;
  }
  if (wsum <= 0) return false;
  out = acc / wsum;
  return true;
}

// Seed: the longest outer-loop facet edge on the u axis, unless pins already anchor the layout.
void Rollout::seed(const TriMesh& mesh) {
  Index placed_count = 0;
  for (char p : placed_) placed_count += p;
  if (placed_count < 2) {
    const auto seg = longest_loop_segment(tp_, mesh, tp_.outer_loop);
    const double L = (mesh.vertices[static_cast<size_t>(tp_.use_vertex[static_cast<size_t>(seg.second)])] - mesh.vertices[static_cast<size_t>(tp_.use_vertex[static_cast<size_t>(seg.first)])]).norm() / c_.length_scale;
    if (placed_count == 1) fail(Errc::unsupported, "the roll-out method needs zero or at least two pins");
    rr_.z[seg.first] = 0;
    rr_.z[seg.second] = L;
    placed_[static_cast<size_t>(seg.first)] = placed_[static_cast<size_t>(seg.second)] = 1;
  }
}

// The rings use j closes edges of: their placed length grows, and their uses join the front.
void Rollout::on_placed(Index j) {
  for (Index k = corners_.start[static_cast<size_t>(j)]; k < corners_.start[static_cast<size_t>(j) + 1]; ++k) {
    const Index cj = corners_.items[static_cast<size_t>(k)];
    // In this triangle, the half-edges starting and ending at j are opposite the two other corners.
    for (Index h : {cj, HalfEdges::prev(cj)}) {
      const size_t hs = static_cast<size_t>(h);
      const Index i = opp_use(hs);
      if (placed_[static_cast<size_t>(i)]) continue;
      if (placed_[static_cast<size_t>(u1(hs))] && placed_[static_cast<size_t>(u2(hs))]) {
        ring_placed_[static_cast<size_t>(i)] += c_.length[hs];
        const double total = ring_total_[static_cast<size_t>(i)];
        pq_.push({total > 0 ? ring_placed_[static_cast<size_t>(i)] / total : 0.0, i});  // a NaN key breaks the heap's order
      }
    }
  }
}

// Places every use, the one with the most of its ring placed first.
void Rollout::grow(const std::function<void(double)>& check) {
  ring_placed_.assign(static_cast<size_t>(n_), 0);
  ring_total_.assign(static_cast<size_t>(n_), 0);
  for (size_t h = 0; h < nh_; ++h) ring_total_[static_cast<size_t>(opp_use(h))] += c_.length[h];
  for (Index u = 0; u < n_; ++u)
    if (placed_[static_cast<size_t>(u)]) on_placed(u);
  Index done = 0;
  while (!pq_.empty()) {
    const Index i = pq_.top().second;
    pq_.pop();
    if (placed_[static_cast<size_t>(i)]) continue;
    Complex p;
    if (!predict(i, true, p)) continue;
    if (!std::isfinite(p.real()) || !std::isfinite(p.imag()))
      fail(Errc::invalid_mesh, "roll-out placed use " + std::to_string(i) +
                                   " at a non-finite position: its triangles' edge lengths span more than double precision can weigh; use the global method or rescale the mesh");
    rr_.z[i] = p;
    placed_[static_cast<size_t>(i)] = 1;
    on_placed(i);
    if (++done % 4096 == 0) check(0.3 * done / n_);
  }
  for (Index u = 0; u < n_; ++u)
    if (!placed_[static_cast<size_t>(u)]) fail(Errc::internal, "roll-out could not reach use " + std::to_string(u));
}

// Gauss-Seidel sweeps with all predictions. Nothing guarantees they contract: on triangles whose
// edge lengths span most of double precision's range they can diverge to overflow. The layout
// kept is the one after the smallest move, and a sweep that leaves any coordinate non-finite ends
// the iteration unconverged.
void Rollout::sweep(const std::function<void(double)>& check) {
  VectorXc best = rr_.z;
  double best_move = std::numeric_limits<double>::infinity();
  for (int sweep = 0; sweep < opt_.max_rollout_sweeps; ++sweep) {
    double move = 0;
    for (Index i = 0; i < n_; ++i) {
      if (fixed_[static_cast<size_t>(i)]) continue;
      Complex p;
      if (!predict(i, false, p)) continue;
      const double d = std::abs(p - rr_.z[i]);
      if (!(d <= move)) move = d;  // NaN included
      rr_.z[i] = p;
    }
    rr_.sweeps = sweep + 1;
    rr_.last_move = move;
    if (!std::isfinite(move) || !rr_.z.allFinite()) break;
    if (move < best_move) {
      best_move = move;
      best = rr_.z;
    }
    if (move < opt_.rollout_tolerance) {
      rr_.converged = true;
      break;
    }
    if (sweep % 16 == 0) check(0.3 + 0.7 * sweep / opt_.max_rollout_sweeps);
  }
  if (!rr_.converged) rr_.z = std::move(best);
}

// The translation gauge without pins: the area-weighted centroid at the origin.
void Rollout::centre() {
  Complex cen{0, 0};
  double w = 0;
  for (Index u = 0; u < n_; ++u) {
    cen += c_.use_area[static_cast<size_t>(u)] * rr_.z[u];
    w += c_.use_area[static_cast<size_t>(u)];
  }
  if (w > 0) rr_.z.array() -= cen / w;
}

}  // namespace

RolloutResult rollout(const TriMesh& mesh, const Topology& tp, const Coefficients& c, const std::vector<LinearRow>& pins,
                      const Options& opt, const std::function<void(double)>& check) {
  Rollout r(tp, c, opt);
  r.place_pins(pins);
  r.seed(mesh);
  r.grow(check);
  r.sweep(check);
  if (pins.empty()) r.centre();
  return r.result();
}

}  // namespace wefm
