#include "wefm/core/method/rollout.hpp"

#include <cmath>
#include <limits>
#include <queue>
#include <string>

#include "wefm/core/sys/error.hpp"
#include "wefm/core/method/gauge.hpp"

namespace wefm {

RolloutResult rollout(const TriMesh& mesh, const Topology& tp, const Coefficients& c, const std::vector<LinearRow>& pins,
                      const Options& opt, const std::function<void(double)>& check) {
  const Index n = tp.use_count;
  const size_t nh = c.alpha.size();
  const double s = opt.s;
  RolloutResult rr;
  rr.z = VectorXc::Zero(n);
  std::vector<char> placed(static_cast<size_t>(n), 0), fixed(static_cast<size_t>(n), 0);
  for (size_t r = 0; r < pins.size(); ++r) {
    if (pins[r].terms.size() != 1) fail(Errc::unsupported, "the roll-out method supports pins only; constraint " + std::to_string(r) + " has " + std::to_string(pins[r].terms.size()) + " terms");
    const auto [u, g] = pins[r].terms[0];
    rr.z[u] = pins[r].rhs / g;
    placed[static_cast<size_t>(u)] = fixed[static_cast<size_t>(u)] = 1;
  }
  // Half-edges opposite each use (the use's predictions), as a CSR table.
  std::vector<Index> start(static_cast<size_t>(n) + 1, 0), opp(nh);
  auto opp_use = [&](size_t h) { return tp.corner_use[static_cast<size_t>(HalfEdges::prev(static_cast<Index>(h)))]; };
  auto u1 = [&](size_t h) { return tp.corner_use[h]; };
  auto u2 = [&](size_t h) { return tp.corner_use[static_cast<size_t>(HalfEdges::next(static_cast<Index>(h)))]; };
  for (size_t h = 0; h < nh; ++h) ++start[static_cast<size_t>(opp_use(h)) + 1];
  for (size_t i = 1; i < start.size(); ++i) start[i] += start[i - 1];
  {
    std::vector<Index> fill(start.begin(), start.end() - 1);
    for (size_t h = 0; h < nh; ++h) opp[static_cast<size_t>(fill[static_cast<size_t>(opp_use(h))]++)] = static_cast<Index>(h);
  }
  auto predict = [&](Index i, bool only_placed, Complex& out) {
    Complex acc{0, 0};
    double wsum = 0;
    for (Index k = start[static_cast<size_t>(i)]; k < start[static_cast<size_t>(i) + 1]; ++k) {
      const size_t h = static_cast<size_t>(opp[static_cast<size_t>(k)]);
      const Index a = u1(h), b = u2(h);
      if (only_placed && (!placed[static_cast<size_t>(a)] || !placed[static_cast<size_t>(b)])) continue;
      const Complex e = rr.z[b] - rr.z[a];
      const double d = std::abs(e);
      const double rho = d > 0 && c.length[h] > 0 ? c.length[h] / d : 1.0;
      const Complex sigma(c.alpha[h], c.beta[h] * std::pow(rho, s));
      const double w = 1.0 / c.beta[h];
      acc += w * (rr.z[a] + sigma * e);
      wsum += w;
    }
    if (wsum <= 0) return false;
    out = acc / wsum;
    return true;
  };
  // Seed: the longest outer-loop facet edge on the u axis, unless pins already anchor the layout.
  Index placed_count = 0;
  for (char p : placed) placed_count += p;
  if (placed_count < 2) {
    const auto seg = longest_loop_segment(tp, mesh, tp.outer_loop);
    const double L = (mesh.vertices[static_cast<size_t>(tp.use_vertex[static_cast<size_t>(seg.second)])] - mesh.vertices[static_cast<size_t>(tp.use_vertex[static_cast<size_t>(seg.first)])]).norm() / c.length_scale;
    if (placed_count == 1) fail(Errc::unsupported, "the roll-out method needs zero or at least two pins");
    rr.z[seg.first] = 0;
    rr.z[seg.second] = L;
    placed[static_cast<size_t>(seg.first)] = placed[static_cast<size_t>(seg.second)] = 1;
  }
  // Ring ratio: 3D length of placed ring edges over the ring's perimeter, largest first.
  std::vector<double> ring_placed(static_cast<size_t>(n), 0), ring_total(static_cast<size_t>(n), 0);
  for (size_t h = 0; h < nh; ++h) ring_total[static_cast<size_t>(opp_use(h))] += c.length[h];
  using Item = std::pair<double, Index>;
  std::priority_queue<Item> pq;
  // Corners per use, to find the rings a newly placed use belongs to.
  std::vector<Index> cstart(static_cast<size_t>(n) + 1, 0), corners(nh);
  for (size_t h = 0; h < nh; ++h) ++cstart[static_cast<size_t>(tp.corner_use[h]) + 1];
  for (size_t i = 1; i < cstart.size(); ++i) cstart[i] += cstart[i - 1];
  {
    std::vector<Index> fill(cstart.begin(), cstart.end() - 1);
    for (size_t h = 0; h < nh; ++h) corners[static_cast<size_t>(fill[static_cast<size_t>(tp.corner_use[h])]++)] = static_cast<Index>(h);
  }
  auto on_placed = [&](Index j) {
    for (Index k = cstart[static_cast<size_t>(j)]; k < cstart[static_cast<size_t>(j) + 1]; ++k) {
      const Index cj = corners[static_cast<size_t>(k)];
      // In this triangle, the half-edges starting and ending at j are opposite the two other corners.
      for (Index h : {cj, HalfEdges::prev(cj)}) {
        const size_t hs = static_cast<size_t>(h);
        const Index i = opp_use(hs);
        if (placed[static_cast<size_t>(i)]) continue;
        if (placed[static_cast<size_t>(u1(hs))] && placed[static_cast<size_t>(u2(hs))]) {
          ring_placed[static_cast<size_t>(i)] += c.length[hs];
          const double total = ring_total[static_cast<size_t>(i)];
          pq.push({total > 0 ? ring_placed[static_cast<size_t>(i)] / total : 0.0, i});  // a NaN key breaks the heap's order
        }
      }
    }
  };
  for (Index u = 0; u < n; ++u)
    if (placed[static_cast<size_t>(u)]) on_placed(u);
  Index done = 0;
  while (!pq.empty()) {
    const Index i = pq.top().second;
    pq.pop();
    if (placed[static_cast<size_t>(i)]) continue;
    Complex p;
    if (!predict(i, true, p)) continue;
    if (!std::isfinite(p.real()) || !std::isfinite(p.imag()))
      fail(Errc::invalid_mesh, "roll-out placed use " + std::to_string(i) +
                                   " at a non-finite position: its triangles' edge lengths span more than double precision can weigh; use the global method or rescale the mesh");
    rr.z[i] = p;
    placed[static_cast<size_t>(i)] = 1;
    on_placed(i);
    if (++done % 4096 == 0) check(0.3 * done / n);
  }
  for (Index u = 0; u < n; ++u)
    if (!placed[static_cast<size_t>(u)]) fail(Errc::internal, "roll-out could not reach use " + std::to_string(u));
  // Gauss-Seidel sweeps with all predictions. Nothing guarantees they contract: on triangles
  // whose edge lengths span most of double precision's range they can diverge to overflow. The
  // layout kept is the one after the smallest move, and a sweep that leaves any coordinate
  // non-finite ends the iteration unconverged.
  VectorXc best = rr.z;
  double best_move = std::numeric_limits<double>::infinity();
  for (int sweep = 0; sweep < opt.max_rollout_sweeps; ++sweep) {
    double move = 0;
    for (Index i = 0; i < n; ++i) {
      if (fixed[static_cast<size_t>(i)]) continue;
      Complex p;
      if (!predict(i, false, p)) continue;
      const double d = std::abs(p - rr.z[i]);
      if (!(d <= move)) move = d;  // NaN included
      rr.z[i] = p;
    }
    rr.sweeps = sweep + 1;
    rr.last_move = move;
    if (!std::isfinite(move) || !rr.z.allFinite()) break;
    if (move < best_move) {
      best_move = move;
      best = rr.z;
    }
    if (move < opt.rollout_tolerance) {
      rr.converged = true;
      break;
    }
    if (sweep % 16 == 0) check(0.3 + 0.7 * sweep / opt.max_rollout_sweeps);
  }
  if (!rr.converged) rr.z = std::move(best);
  if (pins.empty()) {  // translation gauge: area-weighted centroid at the origin
    Complex cen{0, 0};
    double w = 0;
    for (Index u = 0; u < n; ++u) {
      cen += c.use_area[static_cast<size_t>(u)] * rr.z[u];
      w += c.use_area[static_cast<size_t>(u)];
    }
    if (w > 0) rr.z.array() -= cen / w;
  }
  return rr;
}

}  // namespace wefm
