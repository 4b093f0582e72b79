#include "wefm/core/meshing/boundary.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <string>

#include "wefm/core/sys/error.hpp"
#include "wefm/core/meshing/graded_spacing.hpp"

namespace wefm::meshing {
namespace {

struct LoopView {
  const TriMesh& mesh;
  const Topology& topo;
  const VectorXc& uv;
  Index loop;
  size_t size() const { return topo.loop_uses[static_cast<size_t>(loop)].size(); }
  Index use(size_t j) const { return topo.loop_uses[static_cast<size_t>(loop)][j % size()]; }
  const Vec3& xyz(size_t j) const { return mesh.vertices[static_cast<size_t>(topo.use_vertex[static_cast<size_t>(use(j))])]; }
  P2 q(size_t j) const {
    const Complex z = uv[use(j)];
    return P2(z.real(), z.imag());
  }
};

size_t run_count(size_t n, size_t from, size_t to) { return to > from ? to - from : to + n - from; }

// Nodes at sorted 3D arc lengths `params` (from position `from`) along the run of `count` segments.
void place(const LoopView& L, size_t from, size_t count, const std::vector<double>& params, LoopNodes& out) {
  size_t seg = 0;
  double s0 = 0;
  for (double s : params) {
    while (seg + 1 < count && s0 + (L.xyz(from + seg + 1) - L.xyz(from + seg)).norm() <= s) {
      s0 += (L.xyz(from + seg + 1) - L.xyz(from + seg)).norm();
      ++seg;
    }
    const double len = (L.xyz(from + seg + 1) - L.xyz(from + seg)).norm();
    const double f = len > 0 ? std::clamp((s - s0) / len, 0.0, 1.0) : 0.0;
    out.xyz.push_back((1 - f) * L.xyz(from + seg) + f * L.xyz(from + seg + 1));
    out.uv.push_back((1 - f) * L.q(from + seg) + f * L.q(from + seg + 1));
    out.use.push_back(f == 0 ? L.use(from + seg) : (f == 1 ? L.use(from + seg + 1) : -1));
  }
}

}  // namespace

double turning_angle(const Topology& topo, const VectorXc& uv, Index loop, size_t j) {
  const auto& lu = topo.loop_uses[static_cast<size_t>(loop)];
  const size_t n = lu.size();
  const Complex a = uv[lu[(j + n - 1) % n]], b = uv[lu[j]], c = uv[lu[(j + 1) % n]];
  const Complex d1 = b - a, d2 = c - b;
  if (std::abs(d1) == 0 || std::abs(d2) == 0) return 0;
  return std::arg(d2 / d1);
}

double run_length(const TriMesh& mesh, const Topology& topo, Index loop, size_t from, size_t to) {
  static const VectorXc none;
  const LoopView L{mesh, topo, none, loop};
  double len = 0;
  const size_t c = run_count(L.size(), from, to);
  for (size_t k = 0; k < c; ++k) len += (L.xyz(from + k + 1) - L.xyz(from + k)).norm();
  return len;
}

LoopNodes discretise_run(const TriMesh& mesh, const Topology& topo, const VectorXc& uv, Index loop, size_t from, size_t to, Index n) {
  const LoopView L{mesh, topo, uv, loop};
  const double len = run_length(mesh, topo, loop, from, to);
  std::vector<double> params;
  for (Index k = 0; k < n; ++k) params.push_back(len * k / n);
  LoopNodes out;
  place(L, from, run_count(L.size(), from, to), params, out);
  return out;
}

namespace {

// Breaks are decided per mesh vertex so both sides of a repeated edge break at the same points.
std::set<Index> break_vertices(const Topology& topo, const VectorXc& uv, double corner_angle_rad) {
  std::set<Index> breaks;
  // A closed edge (a whole boundary cycle, as derived from a bare mesh) starts at an arbitrary
  // vertex: breaking there would leave a short piece next to a real corner and a cluster of tiny
  // elements around it.
  for (const auto& ch : topo.edges)
    if (!ch.empty() && ch.front() != ch.back()) breaks.insert(ch.front()), breaks.insert(ch.back());
  for (Index l = 0; l < static_cast<Index>(topo.loop_uses.size()); ++l)
    for (size_t j = 0; j < topo.loop_uses[static_cast<size_t>(l)].size(); ++j)
      if (std::fabs(turning_angle(topo, uv, l, j)) > corner_angle_rad)
        breaks.insert(topo.use_vertex[static_cast<size_t>(topo.loop_uses[static_cast<size_t>(l)][j])]);
  return breaks;
}

// Pieces of a loop between breaks: their break positions and uniform segment counts.
struct LoopPieces {
  std::vector<size_t> bp;
  std::vector<Index> counts;
  std::vector<Index> pos_edge;  // loop position -> edge
};

// The pieces of loop l. Also lowers `vertex_size` at each break vertex to the shortest uniform
// segment of the pieces (not given by the caller) that end there: the pieces grade down to it, so a
// short piece does not meet segments many times its length. Per vertex, so both sides of a repeated
// edge get the same nodes.
LoopPieces loop_pieces(const TriMesh& mesh, const Topology& topo, const VectorXc& uv, Index l, double h, const std::set<Index>& breaks,
                       const EdgeNodes& given, std::map<Index, double>& vertex_size) {
  const LoopView L{mesh, topo, uv, l};
  const size_t n = L.size();
  // Loop position -> edge, following the loop's edge uses (loop_uses starts at the first edge).
  std::vector<Index> pos_edge;
  for (const EdgeUse& eu : topo.loops[static_cast<size_t>(l)])
    for (size_t k = 0; k + 1 < topo.edges[static_cast<size_t>(eu.edge)].size(); ++k) pos_edge.push_back(eu.edge);
  if (!given.empty() && pos_edge.size() != n)
    fail(Errc::internal, "loop " + std::to_string(l) + ": edge uses do not cover its boundary positions");
  std::vector<size_t> bp;
  for (size_t j = 0; j < n; ++j)
    if (breaks.count(topo.use_vertex[static_cast<size_t>(L.use(j))])) bp.push_back(j);
  if (bp.empty()) bp.push_back(0);
  std::vector<Index> counts(bp.size());
  std::vector<double> lengths(bp.size());
  Index total = 0;
  for (size_t k = 0; k < bp.size(); ++k) {
    lengths[k] = run_length(mesh, topo, l, bp[k], bp[(k + 1) % bp.size()] + (bp.size() == 1 ? n : 0));
    counts[k] = std::max<Index>(1, static_cast<Index>(std::lround(lengths[k] / h)));
    total += counts[k];
  }
  while (total < 3) {
    const size_t k = static_cast<size_t>(std::max_element(lengths.begin(), lengths.end()) - lengths.begin());
    counts[k]++, total++;
    lengths[k] *= 0.5;
  }
  for (size_t k = 0; k < bp.size(); ++k) {
    if (!pos_edge.empty() && given.count(pos_edge[bp[k] % n])) continue;
    const size_t to = bp.size() == 1 ? bp[k] + n : bp[(k + 1) % bp.size()];
    const double u = run_length(mesh, topo, l, bp[k], to) / static_cast<double>(counts[k]);
    for (size_t j : {bp[k], to}) {
      const Index v = topo.use_vertex[static_cast<size_t>(L.use(j))];
      auto [it, fresh] = vertex_size.emplace(v, u);
      if (!fresh) it->second = std::min(it->second, u);
    }
  }
  return {std::move(bp), std::move(counts), std::move(pos_edge)};
}

// Caller nodes on the piece of `cnt` positions from `from` (length len): their arc length along it
// (closest point on its segments). Each node keeps the caller's exact 3D point, so faces sharing the
// edge share the nodes bit for bit; only its UV comes from the projection.
void place_given(const LoopView& L, size_t from, size_t cnt, double len, const std::vector<Vec3>& given, LoopNodes& nodes) {
  std::vector<std::pair<double, Vec3>> picked;
  for (const Vec3& p : given) {
    double best = 1e300, s_best = 0, s0 = 0;
    for (size_t q = 0; q < cnt; ++q) {
      const Vec3 a = L.xyz(from + q), b = L.xyz(from + q + 1);
      const double l2 = (b - a).squaredNorm();
      const double t = l2 > 0 ? std::clamp((p - a).dot(b - a) / l2, 0.0, 1.0) : 0.0;
      const double d = (a + t * (b - a) - p).norm();
      if (d < best) best = d, s_best = s0 + t * std::sqrt(l2);
      s0 += std::sqrt(l2);
    }
    // Nodes of the edge's other pieces lie off this one.
    if (best <= 1e-6 * len && s_best > 1e-9 * len && s_best < len * (1 - 1e-9)) picked.emplace_back(s_best, p);
  }
  std::sort(picked.begin(), picked.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<double> params{0.0};
  for (const auto& pk : picked) params.push_back(pk.first);
  const size_t first = nodes.xyz.size();
  place(L, from, cnt, params, nodes);
  for (size_t q = 0; q < picked.size(); ++q) nodes.xyz[first + 1 + q] = picked[q].second;
}

}  // namespace

std::vector<LoopNodes> discretise_loops(const TriMesh& mesh, const Topology& topo, const VectorXc& uv, double h, double corner_angle_rad,
                                        const EdgeNodes& given, double gradation) {
  const std::set<Index> breaks = break_vertices(topo, uv, corner_angle_rad);
  std::vector<LoopPieces> pieces;
  std::map<Index, double> vertex_size;
  for (Index l = 0; l < static_cast<Index>(topo.loop_uses.size()); ++l)
    pieces.push_back(loop_pieces(mesh, topo, uv, l, h, breaks, given, vertex_size));
  std::vector<LoopNodes> out;
  for (Index l = 0; l < static_cast<Index>(topo.loop_uses.size()); ++l) {
    const LoopView L{mesh, topo, uv, l};
    const size_t n = L.size();
    const auto& [bp, counts, pos_edge] = pieces[static_cast<size_t>(l)];
    LoopNodes nodes;
    for (size_t k = 0; k < bp.size(); ++k) {
      const size_t from = bp[k], to = bp.size() == 1 ? bp[k] + n : bp[(k + 1) % bp.size()];
      const size_t cnt = run_count(n, from, to);
      const double len = run_length(mesh, topo, l, from, to);
      const auto it = pos_edge.empty() ? given.end() : given.find(pos_edge[from % n]);
      std::vector<double> params;
      if (it != given.end()) {
        place_given(L, from, cnt, len, it->second, nodes);
        continue;
      }
      if (gradation > 0) {
        const double s0 = vertex_size.at(topo.use_vertex[static_cast<size_t>(L.use(from))]);
        const double s1 = vertex_size.at(topo.use_vertex[static_cast<size_t>(L.use(to))]);
        params = graded_spacing(len, h, s0, s1, gradation, counts[k]);
      } else {
        for (Index q = 0; q < counts[k]; ++q) params.push_back(len * q / counts[k]);
      }
      place(L, from, cnt, params, nodes);
    }
    out.push_back(std::move(nodes));
  }
  return out;
}

}  // namespace wefm::meshing
