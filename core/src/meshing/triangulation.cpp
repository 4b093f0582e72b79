#include "wefm/core/meshing/triangulation.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <cstdio>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "wefm/core/sys/error.hpp"
#include "wefm/core/sys/mix64.hpp"

// Internally nodes 0..2 are the super-triangle; the caller's node i is internal i + 3.
namespace wefm::meshing {
namespace {
constexpr Index kSuper = 3;
// Squared distance, relative to the cavity's longest rim edge, below which a new point is an old node.
constexpr double kSameNode2 = 1e-12;
inline int nx(int i) { return (i + 1) % 3; }
inline int pv(int i) { return (i + 2) % 3; }

// Position of cell (x, y) along the Hilbert curve over a 2^16 x 2^16 grid.
std::uint64_t hilbert_index(std::uint32_t x, std::uint32_t y) {
  std::uint64_t d = 0;
  for (std::uint32_t s = 1u << 15; s > 0; s >>= 1) {
    const std::uint32_t rx = (x & s) ? 1 : 0, ry = (y & s) ? 1 : 0;
    d += static_cast<std::uint64_t>(s) * s * ((3 * rx) ^ ry);
    if (ry == 0) {  // rotate the quadrant so the curve stays continuous
      if (rx == 1) x = 65535 - x, y = 65535 - y;  // only the lower bits matter from here
      std::swap(x, y);
    }
  }
  return d;
}

// A biased randomised insertion order (Amenta, Choi and Rote): the nodes shuffled with a fixed
// seed, then cut into rounds that double in size, each round sorted along a Hilbert curve. Random
// order keeps the expected cavity small whatever the boundary's shape; the sorted rounds keep each
// point location walk short. The seed is fixed, so a domain always gets the same triangulation.
std::vector<size_t> insertion_order(const std::vector<P2>& points) {
  const size_t n = points.size();
  std::vector<size_t> order(n);
  for (size_t k = 0; k < n; ++k) order[k] = k;
  std::uint64_t state = 0x9E3779B97F4A7C15ull;  // splitmix64: a counter stepped by the golden ratio, mixed
  for (size_t k = n; k > 1; --k) std::swap(order[k - 1], order[static_cast<size_t>(mix64(state += 0x9E3779B97F4A7C15ull) % k)]);
  P2 lo(1e300, 1e300), hi(-1e300, -1e300);
  for (const P2& p : points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const double span = std::max((hi - lo).maxCoeff(), 1e-300);
  std::vector<std::uint64_t> key(n);
  // A cell per coordinate; one that is not a number (a domain gone bad, refused further on) gets cell 0.
  auto cell = [](double x) { return x > 0 ? (x < 65535 ? static_cast<std::uint32_t>(x) : 65535u) : 0u; };
  for (size_t k = 0; k < n; ++k) {
    const P2 q = (points[k] - lo) / span * 65535.0;
    key[k] = hilbert_index(cell(q.x()), cell(q.y()));
  }
  for (size_t end = n; end > 0;) {
    const size_t begin = end / 2 < 8 ? 0 : end / 2;
    std::sort(order.begin() + static_cast<std::ptrdiff_t>(begin), order.begin() + static_cast<std::ptrdiff_t>(end),
              [&key](size_t a, size_t b) { return key[a] < key[b] || (key[a] == key[b] && a < b); });
    end = begin;
  }
  return order;
}
}  // namespace

Index Triangulation::new_tri(Index a, Index b, Index c) {
  T t;
  t.v = {a, b, c};
  Index id;
  if (!free_.empty()) {
    id = free_.back();
    free_.pop_back();
    t.gen = tris_[id].gen + 1;
    tris_[id] = t;
  } else {
    id = static_cast<Index>(tris_.size());
    tris_.push_back(t);
  }
  vtri_[a] = vtri_[b] = vtri_[c] = id;
  last_ = id;
  return id;
}

void Triangulation::link(Index t, int i, Index s) {
  tris_[t].n[i] = s;
  if (s < 0) return;
  const Index a = tris_[t].v[nx(i)], b = tris_[t].v[pv(i)];
  for (int j = 0; j < 3; ++j)
    if (tris_[s].v[nx(j)] == b && tris_[s].v[pv(j)] == a) {
      tris_[s].n[j] = t;
      tris_[s].c[j] = tris_[t].c[i];
      return;
    }
}

Triangulation::Triangulation(const std::vector<P2>& points, const std::vector<std::array<Index, 2>>& segments) {
  P2 lo(1e300, 1e300), hi(-1e300, -1e300);
  for (const P2& p : points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const P2 c = 0.5 * (lo + hi);
  const double r = std::max((hi - lo).maxCoeff(), 1e-300);
  for (int k = 0; k < 3; ++k) {
    const double a = kPi / 2 + 2 * kPi * k / 3;
    pts_.push_back(c + 50 * r * P2(std::cos(a), std::sin(a)));
  }
  vtri_.assign(3, 0);
  new_tri(0, 1, 2);
  // Every boundary node gets its number first; they are inserted in a randomised order
  // (insertion_order): in the loops' own order, each node along a gently curved boundary lies in
  // the circumcircle of most triangles made so far, and the cavities grow with the node count.
  pts_.insert(pts_.end(), points.begin(), points.end());
  vtri_.resize(pts_.size(), -1);
  for (const size_t k : insertion_order(points))
    if (place(static_cast<Index>(k) + kSuper, last_, nullptr, nullptr) < 0)
      fail(Errc::invalid_state, "boundary node " + std::to_string(k) + " coincides with another node: the domain boundary touches itself");
  std::set<std::pair<Index, Index>> seen;
  for (const auto& s : segments) {
    const std::pair<Index, Index> key = std::minmax(s[0] + kSuper, s[1] + kSuper);
    if (!seen.insert(key).second) {
      scars_.insert(key);
      continue;
    }
    recover(s[0] + kSuper, s[1] + kSuper);
  }
  // Lawson flips restore the constrained Delaunay property after the recovery flips. Four nodes
  // on one circle (the rectangles of a strip whose two sides have nodes at the same stations) have
  // two Delaunay diagonals; the one through the quad's lowest-numbered node is taken, so the
  // triangulation depends on the nodes and their numbering (along the loops) alone, not on the
  // order they went in. The tie flips are capped: among many nodes on one circle they could
  // otherwise chase each other.
  std::deque<std::pair<Index, int>> q;
  for (Index t = 0; t < static_cast<Index>(tris_.size()); ++t)
    for (int i = 0; i < 3; ++i) q.emplace_back(t, i);
  std::int64_t tie_flips = 4 * static_cast<std::int64_t>(tris_.size());
  while (!q.empty()) {
    auto [t, i] = q.front();
    q.pop_front();
    const T& tt = tris_[t];
    if (!tt.live || tt.c[i] || tt.n[i] < 0) continue;
    const Index s = tt.n[i];
    int j = 0;
    while (tris_[s].n[j] != t) ++j;
    const Index a = tt.v[i], b = tt.v[nx(i)], c = tt.v[pv(i)], d = tris_[s].v[j];
    const double in = incircle(pts_[tt.v[0]], pts_[tt.v[1]], pts_[tt.v[2]], pts_[d]);
    const bool tie = in == 0 && std::min({a, b, c, d}) >= kSuper && std::min(a, d) < std::min(b, c) && tie_flips > 0;
    if (in > 0 || tie) {
      if (tie) --tie_flips;
      flip(t, i);
      for (int k = 0; k < 3; ++k) q.emplace_back(t, k), q.emplace_back(s, k);
    }
  }
  mark_inside();
  renumber_slots();
  // Closed loops keep the super-triangle outside; anything else would hand out its nodes as mesh nodes.
  for (const T& tt : tris_)
    if (tt.live && tt.inside && (tt.v[0] < kSuper || tt.v[1] < kSuper || tt.v[2] < kSuper))
      fail(Errc::invalid_state, "the boundary segments do not enclose the domain: the domain boundary is not closed");
}

void Triangulation::renumber_slots() {
  // Slots by their corners' numbers, which run along the loops: refinement takes equal candidates
  // in slot order, and in an order along the boundary its fronts advance along a strip instead of
  // meeting from random places, which leaves more nodes in thin strips.
  // (sorted corners, slot) per live triangle: no two live triangles have the same corners, so the
  // order is that of the corners alone.
  std::vector<std::array<Index, 4>> keys;
  for (Index t = 0; t < static_cast<Index>(tris_.size()); ++t)
    if (tris_[t].live) {
      std::array<Index, 4> k{tris_[t].v[0], tris_[t].v[1], tris_[t].v[2], t};
      std::sort(k.begin(), k.begin() + 3);
      keys.push_back(k);
    }
  std::sort(keys.begin(), keys.end());
  std::vector<Index> live(keys.size());
  for (size_t k = 0; k < keys.size(); ++k) live[k] = keys[k][3];
  std::vector<Index> slot_of(tris_.size(), -1);
  for (size_t k = 0; k < live.size(); ++k) slot_of[static_cast<size_t>(live[k])] = static_cast<Index>(k);
  std::vector<T> out;
  out.reserve(live.size());
  for (Index t : live) {
    T tt = tris_[t];
    for (Index& n : tt.n)
      if (n >= 0) n = slot_of[static_cast<size_t>(n)];
    out.push_back(tt);
  }
  tris_ = std::move(out);
  free_.clear();
  for (Index t = 0; t < static_cast<Index>(tris_.size()); ++t)
    for (Index v : tris_[t].v) vtri_[v] = t;
  last_ = tris_.empty() ? 0 : static_cast<Index>(tris_.size()) - 1;
}

Index Triangulation::locate(const P2& p, Index t, bool stop_at_segments, std::array<Index, 2>* crossed) const {
  if (t < 0 || t >= static_cast<Index>(tris_.size()) || !tris_[t].live) t = last_;
  const size_t cap = 4 * tris_.size() + 64;
  for (size_t step = 0; step < cap; ++step) {
    const T& tt = tris_[t];
    bool moved = false;
    for (int k = 0; k < 3 && !moved; ++k) {
      const int i = static_cast<int>((k + step) % 3);
      if (orient2d(pts_[tt.v[nx(i)]], pts_[tt.v[pv(i)]], p) < 0) {
        if (stop_at_segments && tt.c[i]) {
          if (crossed) *crossed = {tt.v[nx(i)], tt.v[pv(i)]};
          return -2;
        }
        if (tt.n[i] < 0) return -1;
        t = tt.n[i];
        moved = true;
      }
    }
    if (!moved) return t;
  }
  for (Index s = 0; s < static_cast<Index>(tris_.size()); ++s) {
    const T& tt = tris_[s];
    if (!tt.live) continue;
    if (orient2d(pts_[tt.v[0]], pts_[tt.v[1]], p) >= 0 && orient2d(pts_[tt.v[1]], pts_[tt.v[2]], p) >= 0 &&
        orient2d(pts_[tt.v[2]], pts_[tt.v[0]], p) >= 0)
      return s;
  }
  return -1;
}

Index Triangulation::insert(const P2& p, Index hint, std::array<Index, 2>* encroached, const std::function<bool(Index)>* near_ok) {
  const Index v = static_cast<Index>(pts_.size());
  pts_.push_back(p);
  vtri_.push_back(-1);
  const Index made = place(v, hint, encroached, near_ok);
  if (made < 0) pts_.pop_back(), vtri_.pop_back();
  return made;
}

Index Triangulation::place(Index v, Index hint, std::array<Index, 2>* encroached, const std::function<bool(Index)>* near_ok) {
  const P2 p = pts_[static_cast<size_t>(v)];
  std::array<Index, 2> crossed{};
  const Index t0 = locate(p, hint, encroached != nullptr, &crossed);
  if (t0 == -2) {
    *encroached = {crossed[0] - kSuper, crossed[1] - kSuper};
    return -1;
  }
  if (t0 < 0 || !tris_[t0].inside) return -1;
  // Cavity: triangles whose circumcircle holds p, reached without crossing a segment.
  std::vector<Index>& cav = cav_;
  cav.assign(1, t0);
  std::vector<char>& mark = mark_;
  if (mark.size() < tris_.size()) mark.resize(tris_.size(), 0);
  mark[t0] = 1;
  std::vector<Rim>& rim = rim_;
  rim.clear();
  for (size_t k = 0; k < cav.size(); ++k) {
    const T& tt = tris_[cav[k]];
    for (int i = 0; i < 3; ++i) {
      const Index s = tt.n[i];
      const Index a = tt.v[nx(i)], b = tt.v[pv(i)];
      if (s >= 0 && !tt.c[i] && !mark[s]) {
        const T& ss = tris_[s];
        if (incircle(pts_[ss.v[0]], pts_[ss.v[1]], pts_[ss.v[2]], p) > 0) {
          mark[s] = 1;
          cav.push_back(s);
          continue;
        }
      }
      if (s >= 0 && !tt.c[i] && mark[s]) continue;
      rim.push_back({a, b, s, tt.c[i]});
    }
  }
  bool ok = true;
  for (const Rim& r : rim) {
    if (!(orient2d(pts_[r.a], pts_[r.b], p) > 0)) ok = false;
    if (ok && near_ok && r.a >= kSuper && !(*near_ok)(r.a - kSuper)) ok = false;
    if (ok && encroached && r.c && r.a >= kSuper && r.b >= kSuper) {
      // Encroachment zone: points closer to the segment than half its length (the diametral
      // disk widened into a stadium). The disk alone leaves the region above a shared segment
      // end open, where circumcentres then pile up in clusters of tiny elements.
      const P2 ab = pts_[r.b] - pts_[r.a];
      const double l2 = ab.squaredNorm();
      const double t = l2 > 0 ? std::clamp((p - pts_[r.a]).dot(ab) / l2, 0.0, 1.0) : 0.0;
      if ((pts_[r.a] + t * ab - p).squaredNorm() < 0.25 * l2) {
        *encroached = {r.a - kSuper, r.b - kSuper};
        ok = false;
      }
    }
  }
  // A refinement point a rounding away from a node (the apex on an encroached segment where the front
  // already put a node) would make triangles of no area, which refinement then splits without end.
  // (Boundary nodes, inserted without `encroached`, are checked exactly: the caller merged close ones.)
  double scale2 = 0;
  for (const Rim& r : rim) scale2 = std::max(scale2, (pts_[r.b] - pts_[r.a]).squaredNorm());
  for (size_t k = 0; ok && encroached && k < rim.size(); ++k)
    if ((pts_[rim[k].a] - p).squaredNorm() <= kSameNode2 * scale2) ok = false;
  for (Index t : cav) mark[t] = 0;
  if (!ok) return -1;
  const bool inside = tris_[t0].inside;
  for (Index t : cav) {
    tris_[t].live = false;
    free_.push_back(t);
  }
  std::vector<Index>& made = made_;
  made.resize(rim.size());
  for (size_t k = 0; k < rim.size(); ++k) {
    const Index t = new_tri(rim[k].a, rim[k].b, v);
    tris_[t].inside = inside;
    tris_[t].c[2] = rim[k].c;
    made[k] = t;
  }
  for (size_t k = 0; k < rim.size(); ++k) {
    const Index t = made[k];
    if (rim[k].out >= 0) link(t, 2, rim[k].out);
    for (size_t m = 0; m < rim.size(); ++m) {
      if (rim[m].a == rim[k].b) tris_[t].n[0] = made[m];
      if (rim[m].b == rim[k].a) tris_[t].n[1] = made[m];
    }
  }
  return v - kSuper;
}

void Triangulation::flip(Index t, int i) {
  const Index s = tris_[t].n[i];
  int j = 0;
  while (tris_[s].n[j] != t) ++j;
  const Index a = tris_[t].v[i], b = tris_[t].v[nx(i)], c = tris_[t].v[pv(i)], d = tris_[s].v[j];
  const Index nab = tris_[t].n[pv(i)], nca = tris_[t].n[nx(i)], ndc = tris_[s].n[pv(j)], nbd = tris_[s].n[nx(j)];
  const bool cab = tris_[t].c[pv(i)], cca = tris_[t].c[nx(i)], cdc = tris_[s].c[pv(j)], cbd = tris_[s].c[nx(j)];
  T& x = tris_[t];
  ++x.gen;
  ++tris_[s].gen;
  x.v = {a, b, d};
  x.c = {cbd, false, cab};
  T& y = tris_[s];
  y.v = {d, c, a};
  y.c = {cca, false, cdc};
  link(t, 0, nbd);
  link(t, 2, nab);
  tris_[t].n[1] = s;
  link(s, 0, nca);
  link(s, 2, ndc);
  tris_[s].n[1] = t;
  vtri_[a] = vtri_[b] = vtri_[d] = t;
  vtri_[c] = s;
}

std::vector<Index> Triangulation::star(Index a) const {
  std::vector<Index> out{vtri_[a]};
  for (size_t k = 0; k < out.size(); ++k) {
    const T& tt = tris_[out[k]];
    int i = 0;
    while (tt.v[i] != a) ++i;
    for (Index s : {tt.n[nx(i)], tt.n[pv(i)]})
      if (s >= 0 && std::find(out.begin(), out.end(), s) == out.end()) out.push_back(s);
  }
  return out;
}

Index Triangulation::edge_triangle(Index a, Index b, int* i) const {
  // At most one triangle holds the directed edge a -> b: the fan round a is walked one way from
  // vtri_[a], and the other way from it should the walk leave the triangulation, without the list
  // star() builds (recovering every boundary segment asks this twice).
  // A walk longer than the triangulation (a fan that never closes: never in a valid one) ends in the
  // old search over the star.
  const Index start = vtri_[a];
  size_t steps = 0;
  for (const int way : {1, 2}) {
    Index t = start;
    do {
      const T& tt = tris_[t];
      int k = 0;
      while (k < 3 && tt.v[k] != a) ++k;
      if (k == 3 || ++steps > tris_.size()) return edge_triangle_in_star(a, b, i);
      if (tt.v[nx(k)] == b) {
        *i = pv(k);
        return t;
      }
      t = way == 1 ? tt.n[pv(k)] : tt.n[nx(k)];
    } while (t >= 0 && t != start);
    if (t == start) break;  // the fan closed: every triangle round a was seen
  }
  return -1;
}

Index Triangulation::edge_triangle_in_star(Index a, Index b, int* i) const {
  for (Index t : star(a)) {
    const T& tt = tris_[t];
    for (int k = 0; k < 3; ++k)
      if (tt.v[k] == a && tt.v[nx(k)] == b) {
        *i = pv(k);
        return t;
      }
  }
  return -1;
}

void Triangulation::recover(Index a, Index b) {
  auto constrain = [&]() {
    int i;
    bool found = false;
    for (auto [p, q] : {std::pair{a, b}, std::pair{b, a}}) {
      const Index t = edge_triangle(p, q, &i);
      if (t >= 0) {
        tris_[t].c[i] = true;
        found = true;
      }
    }
    return found;
  };
  if (constrain()) return;
  auto fail_on = [&](Index w) {
    fail(Errc::invalid_state, "boundary node " + std::to_string(w - kSuper) + " lies on the boundary segment (" + std::to_string(a - kSuper) + ", " +
                             std::to_string(b - kSuper) + "): the domain boundary touches itself");
  };
  const P2 &pa = pts_[a], &pb = pts_[b];
  std::deque<std::pair<Index, Index>> q;
  Index t = -1, v1 = -1, v2 = -1;
  for (Index s : star(a)) {
    const T& tt = tris_[s];
    int k = 0;
    while (tt.v[k] != a) ++k;
    const double o1 = orient2d(pa, pb, pts_[tt.v[nx(k)]]), o2 = orient2d(pa, pb, pts_[tt.v[pv(k)]]);
    if (o1 == 0 && (pts_[tt.v[nx(k)]] - pa).dot(pb - pa) > 0) fail_on(tt.v[nx(k)]);
    if (o1 < 0 && o2 > 0) {
      t = s, v1 = tt.v[nx(k)], v2 = tt.v[pv(k)];
      break;
    }
  }
  if (t < 0) fail(Errc::internal, "boundary segment (" + std::to_string(a - kSuper) + ", " + std::to_string(b - kSuper) + ") could not be recovered");
  for (;;) {
    q.emplace_back(v1, v2);
    int i;
    const Index cur = edge_triangle(v1, v2, &i);
    // Flipping a segment away would open the boundary, and the outside would leak into the domain.
    if (tris_[cur].c[i])
      fail(Errc::invalid_state, "boundary segments (" + std::to_string(a - kSuper) + ", " + std::to_string(b - kSuper) + ") and (" +
                                    std::to_string(v1 - kSuper) + ", " + std::to_string(v2 - kSuper) +
                                    ") cross: the discretised domain boundary intersects itself");
    const Index s = tris_[cur].n[i];
    int j = 0;
    while (tris_[s].n[j] != cur) ++j;
    const Index w = tris_[s].v[j];
    if (w == b) break;
    const double o = orient2d(pa, pb, pts_[w]);
    if (o == 0) fail_on(w);
    if (o < 0)
      v1 = w;
    else
      v2 = w;
    t = s;
  }
  size_t guard = 0;
  while (!q.empty()) {
    if (++guard > 100000 + 100 * tris_.size()) fail(Errc::internal, "boundary segment recovery did not terminate");
    auto [u, w] = q.front();
    q.pop_front();
    int i;
    const Index tt = edge_triangle(u, w, &i);
    if (tt < 0) continue;
    const Index s = tris_[tt].n[i];
    int j = 0;
    while (tris_[s].n[j] != tt) ++j;
    const Index x = tris_[tt].v[i], y = tris_[s].v[j];
    if (orient2d(pts_[x], pts_[u], pts_[y]) > 0 && orient2d(pts_[x], pts_[y], pts_[w]) > 0) {
      flip(tt, i);
      if (x != a && x != b && y != a && y != b && orient2d(pa, pb, pts_[x]) * orient2d(pa, pb, pts_[y]) < 0) q.emplace_back(x, y);
    } else {
      q.emplace_back(u, w);
    }
  }
  if (!constrain()) fail(Errc::internal, "boundary segment (" + std::to_string(a - kSuper) + ", " + std::to_string(b - kSuper) + ") could not be recovered");
}

void Triangulation::mark_inside() {
  std::vector<int> parity(tris_.size(), -1);
  std::deque<Index> q;
  for (Index t = 0; t < static_cast<Index>(tris_.size()); ++t)
    if (tris_[t].live && (tris_[t].v[0] < kSuper || tris_[t].v[1] < kSuper || tris_[t].v[2] < kSuper)) {
      parity[t] = 0;
      q.push_back(t);
    }
  while (!q.empty()) {
    const Index t = q.front();
    q.pop_front();
    for (int i = 0; i < 3; ++i) {
      const Index s = tris_[t].n[i];
      if (s < 0 || parity[s] >= 0) continue;
      // Across a boundary segment inside turns to outside and back; a scar has the domain on both sides.
      const bool flips = tris_[t].c[i] && !scars_.count(std::minmax(tris_[t].v[nx(i)], tris_[t].v[pv(i)]));
      parity[s] = parity[t] ^ (flips ? 1 : 0);
      q.push_back(s);
    }
  }
  for (Index t = 0; t < static_cast<Index>(tris_.size()); ++t) tris_[t].inside = parity[t] == 1;
}

bool Triangulation::valid() const {
  for (Index t = 0; t < static_cast<Index>(tris_.size()); ++t) {
    const T& tt = tris_[t];
    if (!tt.live) continue;
    if (!(orient2d(pts_[tt.v[0]], pts_[tt.v[1]], pts_[tt.v[2]]) > 0)) return false;
    for (int i = 0; i < 3; ++i) {
      const Index s = tt.n[i];
      if (s < 0) continue;
      const T& ss = tris_[s];
      if (!ss.live) return false;
      bool back = false;
      for (int j = 0; j < 3; ++j)
        back = back || (ss.n[j] == t && ss.v[nx(j)] == tt.v[pv(i)] && ss.v[pv(j)] == tt.v[nx(i)] && ss.c[j] == tt.c[i]);
      if (!back) return false;
      // Constrained Delaunay: no node across an unconstrained edge inside the circumcircle.
      if (!tt.c[i] && tt.inside && ss.inside) {
        int j = 0;
        while (ss.n[j] != t) ++j;
        if (incircle(pts_[tt.v[0]], pts_[tt.v[1]], pts_[tt.v[2]], pts_[ss.v[j]]) > 0) return false;
      }
    }
  }
  return true;
}

std::vector<std::array<Index, 3>> Triangulation::triangles() const {
  std::vector<std::array<Index, 3>> out;
  for (const T& t : tris_)
    if (t.live && t.inside) out.push_back({t.v[0] - kSuper, t.v[1] - kSuper, t.v[2] - kSuper});
  return out;
}

void Triangulation::refine(const std::function<int(Index, Index, Index)>& size, double min_angle_rad, std::int64_t max_nodes,
                           const std::function<void(Index)>& on_insert) {
  const double sin2 = std::sin(min_angle_rad) * std::sin(min_angle_rad);
  auto bad = [&](Index t) {
    const T& tt = tris_[t];
    if (!tt.live || !tt.inside) return false;
    const int cls = size(tt.v[0] - kSuper, tt.v[1] - kSuper, tt.v[2] - kSuper);
    if (cls != 0) return cls > 0;
    const P2 &a = pts_[tt.v[0]], &b = pts_[tt.v[1]], &c = pts_[tt.v[2]];
    // Smallest angle from the shortest edge: sin^2(min) = (2 area / (l_j l_k))^2 over the two others.
    const double l[3] = {(b - c).squaredNorm(), (c - a).squaredNorm(), (a - b).squaredNorm()};
    const int m = static_cast<int>(std::min_element(l, l + 3) - l);
    const double area2 = (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
    return area2 * area2 < sin2 * l[nx(m)] * l[pv(m)];
  };
  std::deque<Index> q;
  for (Index t = 0; t < static_cast<Index>(tris_.size()); ++t) q.push_back(t);
  const std::int64_t cap = max_nodes > 0 ? max_nodes : (std::int64_t(1) << 40);
  while (!q.empty() && node_count() < cap) {
    const Index t = q.front();
    q.pop_front();
    if (!bad(t)) continue;
    const T& tt = tris_[t];
    const P2 &a = pts_[tt.v[0]], &b = pts_[tt.v[1]], &c = pts_[tt.v[2]];
    const P2 ba = b - a, ca = c - a;
    const double d = 2 * (ba.x() * ca.y() - ba.y() * ca.x());
    if (!(std::fabs(d) > 0)) continue;
    const P2 cc = a + P2(ca.y() * ba.squaredNorm() - ba.y() * ca.squaredNorm(), ba.x() * ca.squaredNorm() - ca.x() * ba.squaredNorm()) / d;
    std::array<Index, 2> enc{{-1, -1}};
    Index v = insert(cc, t, &enc);
    if (v < 0 && enc[0] >= 0) {
      // The apex of the equilateral triangle standing on the encroached segment, inside.
      int i;
      Index s = edge_triangle(enc[0] + kSuper, enc[1] + kSuper, &i);
      P2 p0 = pts_[enc[0] + kSuper], p1 = pts_[enc[1] + kSuper];
      if (s < 0 || !tris_[s].inside) std::swap(p0, p1);
      const P2 e = p1 - p0;
      const P2 apex = 0.5 * (p0 + p1) + (std::sqrt(3.0) / 2) * P2(-e.y(), e.x());
      std::array<Index, 2> enc2{{-1, -1}};
      v = insert(apex, t, &enc2);
    }
    if (v < 0) continue;

    on_insert(v);
    for (Index s : star(v + kSuper)) q.push_back(s);
    if (tris_[t].live) q.push_back(t);
  }
}

}  // namespace wefm::meshing
