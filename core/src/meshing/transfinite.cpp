#include "wefm/core/meshing/transfinite.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "wefm/core/sys/clock.hpp"
#include "wefm/core/meshing/size_field.hpp"
#include "wefm/core/sys/error.hpp"

namespace wefm::meshing {

std::array<size_t, 4> transfinite_corners(const Topology& topo, const VectorXc& uv, const std::array<Index, 4>& given) {
  if (topo.loop_uses.size() != 1)
    fail(Errc::unsupported, "transfinite meshing needs a face without holes (this face has " + std::to_string(topo.loop_uses.size()) + " loops)");
  const auto& lu = topo.loop_uses[static_cast<size_t>(topo.outer_loop)];
  if (lu.size() < 4) fail(Errc::unsupported, "transfinite meshing needs at least four boundary vertices");
  std::array<size_t, 4> c{};
  const bool caller = given[0] >= 0 || given[1] >= 0 || given[2] >= 0 || given[3] >= 0;
  if (caller) {
    for (int k = 0; k < 4; ++k) {
      auto it = std::find(lu.begin(), lu.end(), given[static_cast<size_t>(k)]);
      if (it == lu.end()) fail(Errc::invalid_argument, "transfinite corner " + std::to_string(k) + " (use " + std::to_string(given[static_cast<size_t>(k)]) + ") is not a use of the outer loop");
      c[static_cast<size_t>(k)] = static_cast<size_t>(it - lu.begin());
    }
  } else {
    std::vector<std::pair<double, size_t>> turn;
    for (size_t j = 0; j < lu.size(); ++j) turn.emplace_back(turning_angle(topo, uv, topo.outer_loop, j), j);
    std::partial_sort(turn.begin(), turn.begin() + 4, turn.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    for (int k = 0; k < 4; ++k) c[static_cast<size_t>(k)] = turn[static_cast<size_t>(k)].second;
  }
  // Loop order from the first corner (the caller's first, or the lowest position).
  const size_t first = c[0], n = lu.size();
  std::sort(c.begin(), c.end(), [&](size_t a, size_t b) { return (a + n - first) % n < (b + n - first) % n; });
  for (int k = 0; k < 3; ++k)
    if (c[static_cast<size_t>(k)] == c[static_cast<size_t>(k) + 1]) fail(Errc::invalid_argument, "transfinite corners must be four distinct uses");
  return c;
}

std::optional<std::array<size_t, 4>> four_corners(const Topology& topo, const VectorXc& uv) {
  constexpr double kLeast = 30 * kPi / 180, kMost = 150 * kPi / 180, kSide = 20 * kPi / 180;
  if (topo.loop_uses.size() != 1) return std::nullopt;
  const Index l = topo.outer_loop;
  const size_t n = topo.loop_uses[static_cast<size_t>(l)].size();
  std::array<size_t, 4> c{};
  size_t found = 0;
  for (size_t j = 0; j < n; ++j) {
    const double t = turning_angle(topo, uv, l, j);
    if (std::fabs(t) < kSide) continue;
    if (t < kLeast || t > kMost || found == 4) return std::nullopt;
    c[found++] = j;
  }
  if (found != 4) return std::nullopt;
  return c;
}

namespace {

// Before the grid is allocated: a size far below the face's would otherwise exhaust memory.
void check_elements(Index n, Index m, const MeshOptions& o) {
  const std::int64_t elements = static_cast<std::int64_t>(n) * m * (!o.quads ? 2 : o.elements == Elements::Quads ? 4 : 1);
  if (o.max_elements > 0 && elements > o.max_elements)
    fail(Errc::invalid_argument, "the transfinite mesh would have " + std::to_string(elements) + " elements, above max_elements = " + std::to_string(o.max_elements));
}

// Normalised 3D arc length at each node of a side (0 at its first node, 1 at its last).
std::vector<double> arc_parameters(const LoopNodes& side) {
  std::vector<double> t(side.xyz.size(), 0.0);
  for (size_t k = 1; k < t.size(); ++k) t[k] = t[k - 1] + (side.xyz[k] - side.xyz[k - 1]).norm();
  const double total = t.empty() ? 0.0 : t.back();
  for (double& x : t) x = total > 0 ? x / total : 0.0;
  return t;
}

// The four sides (bottom, right, top, left; each with both ends) of the outer loop as the free
// mesher discretises it, so the caller's edge nodes are the sides' nodes. Opposite sides must have
// as many nodes: the grid's rows run from one to the other.
std::array<LoopNodes, 4> sides_from_given(const TriMesh& mesh, const Topology& topo, const VectorXc& uv, const MeshOptions& o,
                                          const EdgeNodes& given, const std::array<size_t, 4>& c) {
  const auto loops = discretise_loops(mesh, topo, uv, o.size, o.corner_angle_deg * kPi / 180.0, given, kSizeGradation);
  const LoopNodes& loop = loops[static_cast<size_t>(topo.outer_loop)];
  const auto& lu = topo.loop_uses[static_cast<size_t>(topo.outer_loop)];
  std::array<size_t, 4> at{};
  for (size_t k = 0; k < 4; ++k) {
    const auto it = std::find(loop.use.begin(), loop.use.end(), lu[c[k]]);
    if (it == loop.use.end()) fail(Errc::unsupported, "transfinite meshing: corner " + std::to_string(k) + " is not a boundary node");
    at[k] = static_cast<size_t>(it - loop.use.begin());
  }
  const size_t n = loop.uv.size();
  std::array<LoopNodes, 4> side;
  for (size_t k = 0; k < 4; ++k)
    for (size_t j = at[k];; j = (j + 1) % n) {
      side[k].uv.push_back(loop.uv[j]), side[k].xyz.push_back(loop.xyz[j]), side[k].use.push_back(loop.use[j]);
      if (j == at[(k + 1) % 4]) break;
    }
  if (side[0].uv.size() != side[2].uv.size() || side[1].uv.size() != side[3].uv.size())
    fail(Errc::unsupported, "transfinite meshing with the caller's edge nodes needs opposite sides with as many nodes (sides have " +
                                std::to_string(side[0].uv.size()) + ", " + std::to_string(side[1].uv.size()) + ", " +
                                std::to_string(side[2].uv.size()) + " and " + std::to_string(side[3].uv.size()) + " nodes)");
  check_elements(static_cast<Index>(side[0].uv.size()) - 1, static_cast<Index>(side[1].uv.size()) - 1, o);
  return side;
}

// Uniform sides at the option's size: opposite sides get the mean of their counts.
std::array<LoopNodes, 4> uniform_sides(const TriMesh& mesh, const Topology& topo, const VectorXc& uv, const MeshOptions& o,
                                       const std::array<size_t, 4>& c) {
  const Index loop = topo.outer_loop;
  double len[4];
  for (size_t k = 0; k < 4; ++k) len[k] = run_length(mesh, topo, loop, c[k], c[(k + 1) % 4]);
  const Index n = std::max<Index>(1, static_cast<Index>(std::lround(0.5 * (len[0] + len[2]) / o.size)));
  const Index m = std::max<Index>(1, static_cast<Index>(std::lround(0.5 * (len[1] + len[3]) / o.size)));
  check_elements(n, m, o);
  std::array<LoopNodes, 4> side;
  for (size_t k = 0; k < 4; ++k) {
    side[k] = discretise_run(mesh, topo, uv, loop, c[k], c[(k + 1) % 4], k % 2 == 0 ? n : m);
    const LoopNodes end = discretise_run(mesh, topo, uv, loop, c[(k + 1) % 4], c[(k + 2) % 4], 1);
    side[k].uv.push_back(end.uv[0]), side[k].xyz.push_back(end.xyz[0]), side[k].use.push_back(end.use[0]);
  }
  return side;
}

// The grid's normals, elements and rails from its nodes (grid numbering j * (n + 1) + i).
void emit_grid(Index n, Index m, bool quads, DomainMesh& out) {
  auto id = [&](Index i, Index j) { return j * (n + 1) + i; };
  // The grid's own normal (cross product of its two rail directions) for the wiggle factor: exact
  // where the grid is, unlike vertex normals near a facetted boundary.
  auto X = [&](Index i, Index j) { return out.xyz[static_cast<size_t>(id(std::clamp<Index>(i, 0, n), std::clamp<Index>(j, 0, m)))]; };
  for (Index j = 0; j <= m; ++j)
    for (Index i = 0; i <= n; ++i) {
      const Vec3 g = (X(i + 1, j) - X(i - 1, j)).cross(X(i, j + 1) - X(i, j - 1));
      if (g.norm() > 0) out.normal[static_cast<size_t>(id(i, j))] = g.normalized();
    }
  out.grid_columns = n + 1;
  out.boundary_nodes = 0;  // grid numbering: boundary nodes are the grid's rim, not a prefix
  out.nodes_per_element = quads ? 4 : 3;
  for (Index j = 0; j < m; ++j)
    for (Index i = 0; i < n; ++i) {
      const Index a = id(i, j), b = id(i + 1, j), cc = id(i + 1, j + 1), d = id(i, j + 1);
      if (quads) {
        out.elements.insert(out.elements.end(), {a, b, cc, d});
      } else if ((out.xyz[static_cast<size_t>(a)] - out.xyz[static_cast<size_t>(cc)]).norm() <=
                 (out.xyz[static_cast<size_t>(b)] - out.xyz[static_cast<size_t>(d)]).norm()) {
        out.elements.insert(out.elements.end(), {a, b, cc, a, cc, d});
      } else {
        out.elements.insert(out.elements.end(), {a, b, d, b, cc, d});
      }
    }
  // Interior rail lines only: the boundary ones are the boundary discretisation, the same 3D
  // points whatever the domain, so they would only blur the comparison of domains.
  for (Index j = 1; j < m; ++j) {
    std::vector<Index> row;
    for (Index i = 0; i <= n; ++i) row.push_back(id(i, j));
    out.rails.push_back(std::move(row));
  }
  for (Index i = 1; i < n; ++i) {
    std::vector<Index> col;
    for (Index j = 0; j <= m; ++j) col.push_back(id(i, j));
    out.rails.push_back(std::move(col));
  }
}

// Halves the grid's cells both ways (all-quad transfinite meshes, as split_into_quads halves a free
// mesh's): the new nodes take the UV middle of their neighbours; on the rim, the 3D chord's middle
// (kept, like the given nodes), so a face beside it given the same edge nodes makes the same ones.
// Inside, the caller lifts them.
void halve_grid(Index& n, Index& m, std::vector<P2>& uv, std::vector<Vec3>& xyz, std::vector<char>& on_side) {
  const Index n2 = 2 * n, m2 = 2 * m;
  auto old_id = [&](Index i, Index j) { return static_cast<size_t>(j * (n + 1) + i); };
  auto new_id = [&](Index i, Index j) { return static_cast<size_t>(j * (n2 + 1) + i); };
  std::vector<P2> uv2(static_cast<size_t>((n2 + 1) * (m2 + 1)), P2::Zero());
  std::vector<Vec3> xyz2(uv2.size(), Vec3::Zero());
  std::vector<char> side2(uv2.size(), 0);
  for (Index j = 0; j <= m2; ++j)
    for (Index i = 0; i <= n2; ++i) {
      // The old nodes around (i, j): one, the two ends of an old edge, or an old cell's four corners.
      const Index i0 = i / 2, i1 = (i + 1) / 2, j0 = j / 2, j1 = (j + 1) / 2;
      const size_t k = new_id(i, j);
      side2[k] = i == 0 || j == 0 || i == n2 || j == m2;
      if (i % 2 == 0 && j % 2 == 0) {
        uv2[k] = uv[old_id(i0, j0)], xyz2[k] = xyz[old_id(i0, j0)];
      } else {
        uv2[k] = 0.25 * (uv[old_id(i0, j0)] + uv[old_id(i1, j0)] + uv[old_id(i0, j1)] + uv[old_id(i1, j1)]);
        if (side2[k]) xyz2[k] = 0.5 * (xyz[old_id(i0, j0)] + xyz[old_id(i1, j1)]);
      }
    }
  n = n2, m = m2;
  uv = std::move(uv2), xyz = std::move(xyz2), on_side = std::move(side2);
}

}  // namespace

void transfinite_mesh(const TriMesh& mesh, const Topology& topo, const VectorXc& uv, const SurfaceMap& map, const MeshOptions& o,
                      const EdgeNodes& given, DomainMesh& out) {
  const double t0 = now();
  const auto c = transfinite_corners(topo, uv, o.corners);
  std::array<LoopNodes, 4> side = given.empty() ? uniform_sides(mesh, topo, uv, o, c) : sides_from_given(mesh, topo, uv, o, given, c);
  const Index n = static_cast<Index>(side[0].uv.size()) - 1, m = static_cast<Index>(side[1].uv.size()) - 1;
  // Sides running in +xi (bottom, top) and +eta (left, right).
  for (size_t k : {size_t(2), size_t(3)}) {
    std::reverse(side[k].uv.begin(), side[k].uv.end());
    std::reverse(side[k].xyz.begin(), side[k].xyz.end());
  }
  const LoopNodes &B = side[0], &R = side[1], &T = side[2], &L = side[3];
  // The blend's parameters: node index over count on uniform sides, else the mean of the two
  // opposite sides' arc-length parameters, so graded edge nodes grade the rows between them.
  std::vector<double> xi(static_cast<size_t>(n) + 1), eta(static_cast<size_t>(m) + 1);
  if (given.empty()) {
    for (Index i = 0; i <= n; ++i) xi[static_cast<size_t>(i)] = double(i) / n;
    for (Index j = 0; j <= m; ++j) eta[static_cast<size_t>(j)] = double(j) / m;
  } else {
    const auto b = arc_parameters(B), t = arc_parameters(T), l = arc_parameters(L), r = arc_parameters(R);
    for (size_t i = 0; i < xi.size(); ++i) xi[i] = 0.5 * (b[i] + t[i]);
    for (size_t j = 0; j < eta.size(); ++j) eta[j] = 0.5 * (l[j] + r[j]);
  }
  auto id = [&](Index i, Index j) { return j * (n + 1) + i; };
  out.uv.assign(static_cast<size_t>((n + 1) * (m + 1)), P2::Zero());
  out.xyz.assign(out.uv.size(), Vec3::Zero());
  std::vector<char> on_side(out.uv.size(), 0);
  for (Index j = 0; j <= m; ++j)
    for (Index i = 0; i <= n; ++i) {
      const size_t k = static_cast<size_t>(id(i, j)), ii = static_cast<size_t>(i), jj = static_cast<size_t>(j);
      const double x = xi[ii], e = eta[jj];
      out.uv[k] = (1 - e) * B.uv[ii] + e * T.uv[ii] + (1 - x) * L.uv[jj] + x * R.uv[jj] -
                  ((1 - x) * (1 - e) * B.uv[0] + x * (1 - e) * B.uv[static_cast<size_t>(n)] + x * e * T.uv[static_cast<size_t>(n)] +
                   (1 - x) * e * T.uv[0]);
      // Boundary nodes keep their exact 3D points (a seam's two sides stay the same points).
      if (j == 0) out.uv[k] = B.uv[ii], out.xyz[k] = B.xyz[ii], on_side[k] = 1;
      else if (j == m) out.uv[k] = T.uv[ii], out.xyz[k] = T.xyz[ii], on_side[k] = 1;
      else if (i == 0) out.uv[k] = L.uv[jj], out.xyz[k] = L.xyz[jj], on_side[k] = 1;
      else if (i == n) out.uv[k] = R.uv[jj], out.xyz[k] = R.xyz[jj], on_side[k] = 1;
    }
  Index n_out = n, m_out = m;
  if (o.quads && o.elements == Elements::Quads) halve_grid(n_out, m_out, out.uv, out.xyz, on_side);
  out.report.time_mesh = now() - t0;
  const double t1 = now();
  out.normal.resize(out.uv.size());
  for (size_t k = 0; k < out.uv.size(); ++k) {
    Vec3 x;
    if (!map.lift(out.uv[k], x, &out.normal[k])) out.report.outside_nodes++;
    if (!on_side[k]) out.xyz[k] = x;
  }
  out.report.time_map = now() - t1;
  emit_grid(n_out, m_out, o.quads, out);
  out.report.transfinite = true;
}

}  // namespace wefm::meshing
