#include "cad_edge_nodes.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <utility>
#include <unordered_map>

#include "wefm/common/linear_size.hpp"

namespace wefm_cad {

namespace {

// A face narrow all along (a needle: a thin step, a strip left between two fillets) is sized by its
// width down to the size at which its boundary takes its share of segments (a needle of length L
// and width w takes about 2 L / (kWidthFactor w) of them), and not below h / kNarrowestEdgeFraction,
// as a pinch: no face can ask for millions of elements along its long edges, and its neighbours,
// graded from them, thousands each. The model's needles share kModelNeedleSegments, each at least
// kNeedleSegments (one 1 / 400 as wide as it is long then keeps slivers): a lone needle, as a slender
// sheet meshed on its own, gets its width across. However long the needle, its floor is at most
// h / kNeedleMostFraction.
constexpr double kNeedleSegments = 2000;
constexpr double kModelNeedleSegments = 40000;
constexpr double kNeedleMostFraction = 8;
// Segments along a strip of width w at this many w have Lo lambda about 0.6 across it (0.87 at 1 w,
// 0.33 at 5 w): a narrow face or part of a face is meshed at this many times its width.
constexpr double kWidthFactor = 2.5;
// Two edges of a face closer than this fraction of the model's diagonal lie on each other: far below
// any width a tessellation at the default deflection (a thousandth) shows, far above the rounding of
// one curve's points computed twice. Not the deflection itself: real gaps and slivers that thin
// exist (a millimetre on a robot two metres across), and their faces are narrow.
constexpr double kCoincident = 1e-6;
// Edge segments shrink towards a pinch of a face (a place narrower than kPinchFraction of the
// face's width, 2 area / perimeter, as where a twisted blend's two sides nearly meet) down to
// h / kPinchFloorFraction: a pinch costs a few dozen segments, as they grow back by g per unit
// length, and so does a narrow arm of the face up to kPinchSegments long; a longer arm gets
// kPinchSegments, as short as that makes them (narrow_floor). nodeocc_kuka's plates have arms 0.03
// to 0.09 wide and up to 100 long: at h / 32 their min Lo lambda was 0.013 to 0.06, now 0.12 and
// up, for 9 % more triangles. Within kCuspReach h of a corner under 10 degrees (a cusp) they do not
// shrink by the width where the face is the corner's wedge (kWedgeShare): shorter chords there only
// narrow the corner's triangles, as they turn towards the edges' common tangent (gmsh_917_fusee's
// min Lo lambda 0.146 with h / 32 there, 0.404 without, at 1/40); the cusp's fan (fan_from_start)
// places the nodes next to it instead.
// Elsewhere only down to h / kNarrowestCornerFraction:
// - a face narrow all along (under h / kNeedleRatio wide: one narrow-face merging could not take)
//   goes down to its needle floor (needle_floor) instead;
// - a face only somewhat narrower in places is graded by its width well enough.
constexpr double kNarrowestEdgeFraction = 300;
// Where two edges touch tangentially (gmsh_Solid_56's face 31) the width goes to 0; at h / 300 the
// triangles there had Lo lambda 0.276, at h / 1000 0.315, for 1 % more triangles on that model.
constexpr double kPinchFloorFraction = 1000;
constexpr double kNarrowestCornerFraction = 32;
constexpr double kCuspReach = 0.5;
// Beside a cusp, a place narrower than this share of the wedge's width at its distance from the tip
// (d sin of the corner) is not the wedge but a strip past it (a plate's arm whose end is sharp): it is
// sized by its width. nodeocc_kuka's face 418 at 1/20 (an arm 0.03 wide, 26 long) had segments of 5
// to 10 and Lo lambda 0.009; at this share 0.048, with no other cad-more model's min lambda changed at
// 1/20, 1/40 or 1/100. At 0.2 or 0.5 pyocc_Ventilator's corner triangles fell from 0.231 to 0.132.
constexpr double kWedgeShare = 0.05;
constexpr double kPinchFraction = 0.25;
constexpr double kPinchSegments = 200;
constexpr double kNeedleRatio = 30;
// A face at least this many times its smaller radius of curvature wide (2 area / perimeter) wraps
// round it: a tube of radius r is about 2 pi r wide, a long half tube pi r, a quarter-round fillet
// about 1.6 r. A short half tube is narrow too: it wraps by its normals (turns_little).
constexpr double kWrapWidth = 2;
// A face whose facet normals all lie within this angle of their mean turns less than about 120
// degrees (a quarter-round fillet along a line turns 90).
constexpr double kDegree = 3.14159265358979 / 180;
constexpr double kLittleTurn = 60 * kDegree;
// The smallest a curved face gets: a hole or tube of radius down to h / 8 keeps six segments around.
constexpr double kSmallestRadiusFraction = 8;
// The fewest elements round a short face that wraps round its seam, below the floor above: with three
// or fewer round the period, a thin tube's mesh reaches round to its own other side (it lies on itself
// twice, or folds away when welded and leaves its edges in no triangle). Only tubes at most h long (a
// hole through a plate, a pin): along a long thin wire isotropic elements that small multiply its
// triangles many times over; such a wire needs a mapped strip instead.
constexpr double kFewestAround = 4;

double distance(const double* a, const double* b) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

// A size along an edge, linear in arc length between samples (s_k, v_k), as common/linear_size.
class SampledSize {
 public:
  SampledSize(const std::vector<double>& s, const std::vector<double>& v) : L_(s.back()) {
    for (size_t k = 0; k + 1 < s.size(); ++k) {
      if (!(s[k + 1] > s[k])) continue;
      double slope = (v[k + 1] - v[k]) / (s[k + 1] - s[k]);
      if (std::fabs(slope) < 1e-12) slope = 0;
      size_.append(s[k], s[k + 1], v[k], slope);
    }
  }
  double total() const { return size_.total(); }  // the integral of 1 / size over the edge
  // Arc length at which the integral reaches `phi`.
  double inverse(double phi) const { return size_.empty() ? L_ : size_.inverse(phi); }

 private:
  double L_;
  wefm_common::LinearSize size_;
};

// Sizes at samples no faster-growing than g per unit length in either direction (the smallest
// function above which nothing is, with slope at most g): two sweeps along the samples.
void grade(const std::vector<double>& s, std::vector<double>& v, double g) {
  for (size_t k = 1; k < s.size(); ++k) v[k] = std::min(v[k], v[k - 1] + g * (s[k] - s[k - 1]));
  for (size_t k = s.size() - 1; k-- > 0;) v[k] = std::min(v[k], v[k + 1] + g * (s[k + 1] - s[k]));
}

// The size is linear between samples. Where both ends of a piece were lowered (an edge shorter than
// the sampling step between two short neighbours), the line between them would keep it small all
// along, thousands of segments where the grading allows it to rise by g per unit length from each
// end: the peak of that rise, capped by `cap` (the profile before the ends were lowered, on the same
// samples), becomes a sample.
void add_peaks(std::vector<double>& s, std::vector<double>& v, const std::vector<double>& cap, double g) {
  if (!(g > 0) || s.size() < 2) return;
  std::vector<double> s2{s[0]}, v2{v[0]};
  for (size_t k = 0; k + 1 < s.size(); ++k) {
    const double a = s[k], b = s[k + 1], va = v[k], vb = v[k + 1];
    const double peak = (vb - va + g * (a + b)) / (2 * g);
    if (peak > a && peak < b) {
      const double t = (peak - a) / (b - a);
      const double at = std::min(va + g * (peak - a), cap[k] + t * (cap[k + 1] - cap[k]));
      if (at > (va + t * (vb - va)) * (1 + 1e-9)) s2.push_back(peak), v2.push_back(at);
    }
    s2.push_back(b), v2.push_back(vb);
  }
  s = std::move(s2);
  v = std::move(v2);
}

// Nodes at the given arc lengths (sorted, first 0, last the full length) along the edge's chain.
EdgeNodes place(const CadFace& face, const CadEdge& edge, const std::vector<double>& targets) {
  const size_t m = edge.vertices.size();
  std::vector<const double*> p(m);
  for (size_t i = 0; i < m; ++i) p[i] = &face.xyz[3 * static_cast<size_t>(edge.vertices[i])];
  std::vector<double> s(m, 0.0);  // arc length at each chain vertex
  for (size_t i = 1; i < m; ++i) s[i] = s[i - 1] + distance(p[i - 1], p[i]);
  EdgeNodes out;
  out.xyz.insert(out.xyz.end(), p[0], p[0] + 3);
  size_t seg = 1;
  for (size_t k = 1; k + 1 < targets.size(); ++k) {
    const double target = targets[k];
    while (seg + 1 < m && s[seg] < target) ++seg;
    const double len = s[seg] - s[seg - 1];
    const double t = len > 0 ? std::clamp((target - s[seg - 1]) / len, 0.0, 1.0) : 0.0;
    for (int c = 0; c < 3; ++c) out.xyz.push_back(p[seg - 1][c] + t * (p[seg][c] - p[seg - 1][c]));
  }
  out.xyz.insert(out.xyz.end(), p[m - 1], p[m - 1] + 3);
  return out;
}

// A model edge's wanted size at sample arc lengths along its chain.
struct SizeProfile {
  std::vector<double> s, v;
};

// The arc lengths of a chain's vertices.
std::vector<double> chain_arcs(const CadFace& f, const CadEdge& e) {
  std::vector<double> s(e.vertices.size(), 0.0);
  for (size_t i = 1; i < s.size(); ++i)
    s[i] = s[i - 1] + distance(&f.xyz[3 * static_cast<size_t>(e.vertices[i - 1])], &f.xyz[3 * static_cast<size_t>(e.vertices[i])]);
  return s;
}

// The chain's vertices and points between them no more than `step` apart, as arc lengths.
std::vector<double> sample_arcs(const std::vector<double>& chain, double step) {
  std::vector<double> out{0.0};
  for (size_t i = 1; i < chain.size(); ++i) {
    const double a = chain[i - 1], b = chain[i];
    const auto n = std::isfinite(step) && step > 0 ? static_cast<long long>(std::min(1e4, std::ceil((b - a) / step))) : 1LL;
    for (long long k = 1; k <= n; ++k) out.push_back(a + (b - a) * static_cast<double>(k) / static_cast<double>(std::max(1LL, n)));
  }
  return out;
}

// The point at arc length `s` along a chain with arc lengths `arcs`.
std::array<double, 3> point_at(const CadFace& f, const CadEdge& e, const std::vector<double>& arcs, double s) {
  const size_t hi = static_cast<size_t>(std::upper_bound(arcs.begin(), arcs.end(), s) - arcs.begin());
  const size_t i = std::clamp<size_t>(hi, 1, arcs.size() - 1);
  const double* a = &f.xyz[3 * static_cast<size_t>(e.vertices[i - 1])];
  const double* b = &f.xyz[3 * static_cast<size_t>(e.vertices[i])];
  const double len = arcs[i] - arcs[i - 1];
  const double t = len > 0 ? std::clamp((s - arcs[i - 1]) / len, 0.0, 1.0) : 0.0;
  return {a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2])};
}

// An edge's segments at most its radius of curvature (about six to a full turn, three to a half
// circle: two segments on a half circle put a chord through the axis that the other half's mesh may
// use too), down to `floor`. The radius at a chain vertex is the mean of its two chain segments over
// the angle between them; a sample gets the smaller of the radii at the ends of its chain segment.
// The turn of edge e's facet chain at chain vertex i1 between i0 and i2, radians, and the mean length
// of its two segments there (0 where one has none).
struct ChainTurn {
  double angle = 0, mean_length = 0;
};
ChainTurn chain_turn_at(const CadFace& f, const CadEdge& e, size_t i0, size_t i1, size_t i2) {
  auto at = [&](size_t i) { return &f.xyz[3 * static_cast<size_t>(e.vertices[i])]; };
  const double *a = at(i0), *b = at(i1), *c = at(i2);
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - b[0], c[1] - b[1], c[2] - b[2]};
  const double lu = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]), lv = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  if (!(lu > 0) || !(lv > 0)) return {};
  return {std::acos(std::clamp((u[0] * v[0] + u[1] * v[1] + u[2] * v[2]) / (lu * lv), -1.0, 1.0)), 0.5 * (lu + lv)};
}

void lower_by_turning(const CadFace& f, const CadEdge& e, double floor, SizeProfile& p) {
  const size_t m = e.vertices.size();
  if (m < 3) return;
  const bool closed = e.vertices.front() == e.vertices.back();
  std::vector<double> radius(m, std::numeric_limits<double>::infinity());
  auto turning = [&](size_t i0, size_t i1, size_t i2) {
    const ChainTurn t = chain_turn_at(f, e, i0, i1, i2);
    return t.mean_length > 0 && t.angle > 1e-3 ? t.mean_length / t.angle : std::numeric_limits<double>::infinity();
  };
  for (size_t i = 1; i + 1 < m; ++i) radius[i] = turning(i - 1, i, i + 1);
  if (closed) radius[0] = radius[m - 1] = turning(m - 2, 0, 1);
  else radius[0] = radius[1], radius[m - 1] = radius[m - 2];
  const std::vector<double> arcs = chain_arcs(f, e);
  for (size_t k = 0, i = 1; k < p.s.size(); ++k) {
    while (i + 1 < m && arcs[i] < p.s[k]) ++i;
    const double r = std::min(radius[i - 1], radius[i]);
    if (std::isfinite(r)) p.v[k] = std::min(p.v[k], std::max(floor, r));
  }
}

// Two boundary points nearer each other than this fraction of the way round the loop between them
// face each other across the face: a strip narrower than the edge's segments, or a corner sharper
// than about 20 degrees. Points just round a blunter corner do not.
constexpr double kAcrossRatio = 0.35;
// Two chain segments within about 8 degrees of parallel face each other along their overlap.
constexpr double kParallelCos = 0.99;

// Which side of each boundary segment (chain vertex i to i + 1 of an edge) the face lies on, from
// the facet corner across it. Unknown on a seam, whose segments have facets on both sides.
class FaceSide {
 public:
  explicit FaceSide(const CadFace& f) : f_(f) {
    for (size_t t = 0; t + 2 < f.triangles.size(); t += 3)
      for (size_t c = 0; c < 3; ++c) {
        const auto [it, fresh] = opposite_.emplace(key(f.triangles[t + c], f.triangles[t + (c + 1) % 3]), f.triangles[t + (c + 2) % 3]);
        if (!fresh) it->second = -1;
      }
  }
  // Whether x lies on the face's side of segment i of edge e (on its line counts as on that side;
  // so does anything beside a seam).
  bool inward(size_t e, size_t i, const double* x) const {
    const CadEdge& ed = f_.edges[e];
    const auto it = opposite_.find(key(ed.vertices[i], ed.vertices[i + 1]));
    if (it == opposite_.end() || it->second < 0) return true;
    const double* a = &f_.xyz[3 * static_cast<size_t>(ed.vertices[i])];
    const double* b = &f_.xyz[3 * static_cast<size_t>(ed.vertices[i + 1])];
    const double* o = &f_.xyz[3 * static_cast<size_t>(it->second)];
    const double d[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    double in[3] = {o[0] - a[0], o[1] - a[1], o[2] - a[2]};
    const double t = dd > 0 ? (in[0] * d[0] + in[1] * d[1] + in[2] * d[2]) / dd : 0.0;
    for (int c = 0; c < 3; ++c) in[c] -= t * d[c];
    return (x[0] - a[0]) * in[0] + (x[1] - a[1]) * in[1] + (x[2] - a[2]) * in[2] >= 0;
  }

 private:
  static unsigned long long key(int32_t a, int32_t b) {
    return static_cast<unsigned long long>(static_cast<uint32_t>(std::min(a, b))) << 32 | static_cast<uint32_t>(std::max(a, b));
  }
  const CadFace& f_;
  std::unordered_map<unsigned long long, int32_t> opposite_;  // segment -> facet corner across, -1 both sides
};

// Per edge of the face, its box grown by `reach` (min x, y, z, max x, y, z): most edges are too far
// from a point to look at.
std::vector<std::array<double, 6>> edge_boxes(const CadFace& f, double reach) {
  std::vector<std::array<double, 6>> box(f.edges.size(), {1e300, 1e300, 1e300, -1e300, -1e300, -1e300});
  for (size_t e = 0; e < f.edges.size(); ++e)
    for (int32_t v : f.edges[e].vertices)
      for (int c = 0; c < 3; ++c) {
        box[e][c] = std::min(box[e][c], f.xyz[3 * static_cast<size_t>(v) + c] - reach);
        box[e][c + 3] = std::max(box[e][c + 3], f.xyz[3 * static_cast<size_t>(v) + c] + reach);
      }
  return box;
}

// Where point q falls on segment p0-p1: the parameter of its projection on the segment's line (0 on
// a degenerate segment) and its distance to the nearest point of the segment.
struct Foot {
  double t, distance;
};

Foot foot_on_segment(const double* q, const double* p0, const double* p1) {
  const double d[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
  const double w[3] = {q[0] - p0[0], q[1] - p0[1], q[2] - p0[2]};
  const double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  const double t = dd > 0 ? (d[0] * w[0] + d[1] * w[1] + d[2] * w[2]) / dd : 0.0, on = std::clamp(t, 0.0, 1.0);
  const double x[3] = {w[0] - on * d[0], w[1] - on * d[1], w[2] - on * d[2]};
  return {t, std::sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2])};
}

// The width of the face at each sample of its edges, reported with the sample's point to
// `width_at`: the distance from a sample to the nearest point of another edge of the face that lies
// across the face from it (on another loop, or far round the same loop compared with the distance,
// and each on the face's side of the other). Widths above `reach` do not matter and are not
// searched for; distances up to `coincide` are none: two edges of a face that lie on each other are
// one curve twice (a closed surface bounded by two edges where one seam would do), and the face
// reaches round from one to the other.
void lower_by_width(const CadFace& f, double reach, double coincide,
                    const std::function<void(long long, size_t, double, const std::array<double, 3>&)>& width_at,
                    const std::map<long long, SizeProfile>& profiles) {
  struct Use {
    size_t loop;
    double offset;
    bool reversed;
  };
  const size_t ne = f.edges.size();
  std::vector<std::vector<double>> arcs(ne);
  std::vector<std::vector<Use>> uses(ne);
  std::vector<double> loop_length;
  for (size_t e = 0; e < ne; ++e)
    if (!f.edges[e].degenerated && f.edges[e].vertices.size() >= 2) arcs[e] = chain_arcs(f, f.edges[e]);
  for (const auto& loop : f.loops) {
    double offset = 0;
    for (const CadEdgeUse& u : loop) {
      const auto e = static_cast<size_t>(u.edge);
      if (e >= ne || arcs[e].empty()) continue;
      uses[e].push_back({loop_length.size(), offset, u.reversed});
      offset += arcs[e].back();
    }
    loop_length.push_back(offset);
  }
  const FaceSide side(f);
  const std::vector<std::array<double, 6>> box = edge_boxes(f, reach);
  // Of all ways round the loops between arc sp on edge a and arc sq on edge b, the shortest
  // (infinite between different loops).
  auto round_loop = [&](size_t a, double sp, size_t b, double sq) {
    double best = std::numeric_limits<double>::infinity();
    for (const Use& ua : uses[a])
      for (const Use& ub : uses[b]) {
        if (ua.loop != ub.loop) continue;
        const double pa = ua.offset + (ua.reversed ? arcs[a].back() - sp : sp);
        const double pb = ub.offset + (ub.reversed ? arcs[b].back() - sq : sq);
        const double d = std::fabs(pa - pb);
        best = std::min({best, d, loop_length[ua.loop] - d});
      }
    return best;
  };
  for (size_t a = 0; a < ne; ++a) {
    const auto it = profiles.find(f.edges[a].id);
    if (arcs[a].empty() || uses[a].empty() || it == profiles.end()) continue;
    const std::vector<double>& samples = it->second.s;
    for (size_t k = 0; k < samples.size(); ++k) {
      const auto p = point_at(f, f.edges[a], arcs[a], samples[k]);
      // The segment of edge a that the sample lies on.
      const size_t ia = std::min<size_t>(arcs[a].size() - 2,
                                         static_cast<size_t>(std::max<std::ptrdiff_t>(0, std::upper_bound(arcs[a].begin(), arcs[a].end(), samples[k]) - arcs[a].begin() - 1)));
      double width = reach;
      for (size_t b = 0; b < ne; ++b) {
        if (b == a || arcs[b].empty() || uses[b].empty() || f.edges[b].id == f.edges[a].id) continue;
        if (p[0] < box[b][0] || p[1] < box[b][1] || p[2] < box[b][2] || p[0] > box[b][3] || p[1] > box[b][4] || p[2] > box[b][5]) continue;
        const CadEdge& eb = f.edges[b];
        for (size_t i = 0; i + 1 < eb.vertices.size(); ++i) {
          const double* q0 = &f.xyz[3 * static_cast<size_t>(eb.vertices[i])];
          const double* q1 = &f.xyz[3 * static_cast<size_t>(eb.vertices[i + 1])];
          const Foot foot = foot_on_segment(p.data(), q0, q1);
          const double t = std::clamp(foot.t, 0.0, 1.0), dist = foot.distance;
          if (dist >= width || dist <= coincide) continue;
          const double sq = arcs[b][i] + t * (arcs[b][i + 1] - arcs[b][i]);
          // Across the face, not across a hole or round the outside: each point on the face's
          // side of the other's segment.
          const double qx[3] = {q0[0] + t * (q1[0] - q0[0]), q0[1] + t * (q1[1] - q0[1]), q0[2] + t * (q1[2] - q0[2])};
          if (!side.inward(a, ia, qx) || !side.inward(b, i, p.data())) continue;
          if (dist < kAcrossRatio * round_loop(a, samples[k], b, sq)) width = dist;
        }
      }
      if (width < reach) width_at(f.edges[a].id, k, width, p);
    }
  }
}

// The parameters (s on p0-p1, t on q0-q1, both in [0, 1]) of the closest points of two segments.
std::pair<double, double> closest_on_segments(const double* p0, const double* p1, const double* q0, const double* q1) {
  double d1[3], d2[3], r[3];
  for (int c = 0; c < 3; ++c) d1[c] = p1[c] - p0[c], d2[c] = q1[c] - q0[c], r[c] = p0[c] - q0[c];
  auto dot = [](const double* x, const double* y) { return x[0] * y[0] + x[1] * y[1] + x[2] * y[2]; };
  const double a = dot(d1, d1), e = dot(d2, d2), f = dot(d2, r);
  if (!(a > 0) && !(e > 0)) return {0.0, 0.0};
  if (!(a > 0)) return {0.0, std::clamp(f / e, 0.0, 1.0)};
  const double c = dot(d1, r);
  if (!(e > 0)) return {std::clamp(-c / a, 0.0, 1.0), 0.0};
  const double b = dot(d1, d2), denom = a * e - b * b;
  double s = denom > 1e-14 * a * e ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
  double t = (b * s + f) / e;
  if (t < 0) t = 0, s = std::clamp(-c / a, 0.0, 1.0);
  else if (t > 1) t = 1, s = std::clamp((b - c) / a, 0.0, 1.0);
  return {s, t};
}

// Where point q projects inside segment p0-p1 (arc lengths s0, s1), nearer than `reach` and farther
// than `coincide`: that arc length, a sample of the segment's edge.
void add_facing_end(const double* q, const double* p0, const double* p1, double s0, double s1, double reach, double coincide,
                    std::vector<double>& samples) {
  const Foot foot = foot_on_segment(q, p0, p1);
  if (foot.t > 0 && foot.t < 1 && foot.distance < reach && foot.distance > coincide) samples.push_back(s0 + foot.t * (s1 - s0));
}

// Whether segments p0-p1 and q0-q1 run within kParallelCos of parallel (either way).
bool parallel(const double* p0, const double* p1, const double* q0, const double* q1) {
  double u[3], v[3];
  for (int c = 0; c < 3; ++c) u[c] = p1[c] - p0[c], v[c] = q1[c] - q0[c];
  const double uv = u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
  const double uu = u[0] * u[0] + u[1] * u[1] + u[2] * u[2], vv = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
  return uu > 0 && vv > 0 && std::fabs(uv) >= kParallelCos * std::sqrt(uu * vv);
}

// Where two edges of a face pass closest to each other inside chain segments of both (two skew
// segments, as across a pinch of a twisted blend), no chain vertex lies at the narrowest place and
// the samples on either side may be several times as wide: the arc lengths of those closest points,
// nearer than `reach` and farther than `coincide` apart, become samples of both edges' sizes.
void add_pinch_samples(const CadFace& f, double reach, double coincide, std::map<long long, std::vector<double>>& extra) {
  const size_t ne = f.edges.size();
  std::vector<std::vector<double>> arcs(ne);
  for (size_t e = 0; e < ne; ++e)
    if (!f.edges[e].degenerated && f.edges[e].vertices.size() >= 2) arcs[e] = chain_arcs(f, f.edges[e]);
  const std::vector<std::array<double, 6>> box = edge_boxes(f, reach);
  auto at = [&](int32_t v) { return &f.xyz[3 * static_cast<size_t>(v)]; };
  for (size_t a = 0; a < ne; ++a)
    for (size_t b = a + 1; b < ne; ++b) {
      if (arcs[a].empty() || arcs[b].empty() || f.edges[a].id == f.edges[b].id) continue;
      bool apart = false;
      for (int c = 0; c < 3; ++c) apart = apart || box[a][c] > box[b][c + 3] || box[b][c] > box[a][c + 3];
      if (apart) continue;
      const CadEdge &ea = f.edges[a], &eb = f.edges[b];
      for (size_t i = 0; i + 1 < ea.vertices.size(); ++i)
        for (size_t j = 0; j + 1 < eb.vertices.size(); ++j) {
          const double *p0 = at(ea.vertices[i]), *p1 = at(ea.vertices[i + 1]), *q0 = at(eb.vertices[j]), *q1 = at(eb.vertices[j + 1]);
          if (parallel(p0, p1, q0, q1)) {
            // No single closest pair: where one's end faces the other (a tongue or a slot between
            // parallel edges) is where the narrow stretch begins and ends.
            add_facing_end(q0, p0, p1, arcs[a][i], arcs[a][i + 1], reach, coincide, extra[ea.id]);
            add_facing_end(q1, p0, p1, arcs[a][i], arcs[a][i + 1], reach, coincide, extra[ea.id]);
            add_facing_end(p0, q0, q1, arcs[b][j], arcs[b][j + 1], reach, coincide, extra[eb.id]);
            add_facing_end(p1, q0, q1, arcs[b][j], arcs[b][j + 1], reach, coincide, extra[eb.id]);
          }
          const auto [s, t] = closest_on_segments(p0, p1, q0, q1);
          if (!(s > 0 && s < 1 && t > 0 && t < 1)) continue;
          double x[3], y[3];
          for (int c = 0; c < 3; ++c) x[c] = p0[c] + s * (p1[c] - p0[c]), y[c] = q0[c] + t * (q1[c] - q0[c]);
          const double d = distance(x, y);
          if (d >= reach || d <= coincide) continue;
          extra[ea.id].push_back(arcs[a][i] + s * (arcs[a][i + 1] - arcs[a][i]));
          extra[eb.id].push_back(arcs[b][j] + t * (arcs[b][j + 1] - arcs[b][j]));
        }
    }
}

long long uniform_count(double length, double h, bool closed) { return std::max<long long>(closed ? 3 : 1, std::llround(length / h)); }

// Model vertices as the chain ends that coincide (within `tol`), numbered in order of appearance;
// a hash of grid cells of side `tol` finds the candidates.
class VertexIds {
 public:
  explicit VertexIds(double tol) : tol_(tol > 0 ? tol : 1e-300) {}
  int of(const double* p) {
    long long c[3];
    for (int k = 0; k < 3; ++k) c[k] = static_cast<long long>(std::floor(p[k] / tol_));
    for (long long dx = -1; dx <= 1; ++dx)
      for (long long dy = -1; dy <= 1; ++dy)
        for (long long dz = -1; dz <= 1; ++dz) {
          const auto range = cells_.equal_range(key(c[0] + dx, c[1] + dy, c[2] + dz));
          for (auto it = range.first; it != range.second; ++it) {
            const auto& q = pts_[static_cast<size_t>(it->second)];
            if (std::fabs(q[0] - p[0]) <= tol_ && std::fabs(q[1] - p[1]) <= tol_ && std::fabs(q[2] - p[2]) <= tol_) return it->second;
          }
        }
    pts_.push_back({p[0], p[1], p[2]});
    const int id = static_cast<int>(pts_.size()) - 1;
    cells_.emplace(key(c[0], c[1], c[2]), id);
    return id;
  }
  size_t size() const { return pts_.size(); }

 private:
  static unsigned long long key(long long i, long long j, long long k) {
    return static_cast<unsigned long long>(i) * 73856093ULL ^ static_cast<unsigned long long>(j) * 19349663ULL ^
           static_cast<unsigned long long>(k) * 83492791ULL;
  }
  double tol_;
  std::vector<std::array<double, 3>> pts_;
  std::unordered_multimap<unsigned long long, int> cells_;
};

// A model edge as the chain of the first face that has it, with its size and end vertices.
struct Chain {
  const CadFace* face;
  const CadEdge* edge;
  double length, size;
  bool closed;
  int v0, v1;
};

// How far an edge's facet chain turns in all, radians: pi for a half circle.
double chain_turn(const CadFace& f, const CadEdge& e) {
  double turn = 0;
  for (size_t i = 1; i + 1 < e.vertices.size(); ++i) turn += chain_turn_at(f, e, i - 1, i, i + 1).angle;
  return turn;
}

// An edge turning by more than this with one segment (a half circle of a hole smaller than the
// floor of lower_by_turning) gets two: its chord would be the circle's diameter, and an annulus whose
// two circles are each split at the same diameter had both chords on one line, the face between
// them of no area (nodeocc_battleship's faces 195 and 245 at 0.3 of the diagonal).
constexpr double kOneSegmentTurn = 2.0944;  // 120 degrees

void at_least_two_per_half_turn(const std::map<long long, Chain>& chains, std::map<long long, std::vector<double>>& targets) {
  for (const auto& [id, c] : chains) {
    auto& t = targets[id];
    if (t.size() == 2 && !c.closed && t.back() > 0 && chain_turn(*c.face, *c.edge) > kOneSegmentTurn) t = {0.0, 0.5 * t.back(), t.back()};
  }
}

// A loop of one segment per edge and two edges (an arc and its chord: a sliver between a fillet
// and a plane, a circular segment) would be its two chords on one line, the face between them of
// no area. Its longest edge with one segment gets its middle, loop by loop, until every loop has at
// least three segments.
void at_least_three_per_loop(const CadModel& model, std::map<long long, std::vector<double>>& targets) {
  for (const CadFace& f : model.faces) {
    if (!f.error.empty()) continue;
    for (const auto& loop : f.loops) {
      for (;;) {
        size_t segments = 0;
        long long longest = -1;
        double length = 0;
        for (const CadEdgeUse& u : loop) {
          const auto e = static_cast<size_t>(u.edge);
          if (e >= f.edges.size()) continue;
          const auto it = targets.find(f.edges[e].id);
          if (it == targets.end() || it->second.size() < 2) continue;
          segments += it->second.size() - 1;
          if (it->second.size() == 2 && it->second.back() > length) length = it->second.back(), longest = it->first;
        }
        if (segments >= 3 || longest < 0 || !(length > 0)) break;
        targets[longest] = {0.0, 0.5 * length, length};
      }
    }
  }
}

// The length of a face's loops: a seam counts twice, as it bounds the domain twice.
double face_perimeter(const CadFace& f) {
  double perimeter = 0;
  for (const auto& loop : f.loops)
    for (const CadEdgeUse& u : loop) perimeter += chain_length(f, f.edges[static_cast<size_t>(u.edge)]);
  return perimeter;
}

// Whether a face's width would size it below h / kNeedleMostFraction: a needle.
bool needle(const CadFace& f, double h) { return kWidthFactor * face_width(f) < h / kNeedleMostFraction; }

// The segments each needle of the model may take along its boundary (kModelNeedleSegments).
double needle_segments(const CadModel& model, double h) {
  const auto needles = std::count_if(model.faces.begin(), model.faces.end(), [&](const CadFace& f) { return f.error.empty() && needle(f, h); });
  return std::max(kNeedleSegments, kModelNeedleSegments / static_cast<double>(std::max<std::ptrdiff_t>(1, needles)));
}

// The smallest size a face narrower than h gets by its width, with `segments` along its boundary
// (needle_segments), between h / kNarrowestEdgeFraction and h / kNeedleMostFraction.
double needle_floor(const CadFace& f, double h, double segments) {
  return std::clamp(face_perimeter(f) / segments, h / kNarrowestEdgeFraction, h / kNeedleMostFraction);
}

// The face's width at one sample of one of its edges (lower_by_width), and whether the sample lies
// within kCuspReach h of a cusp (a corner under 10 degrees).
struct Across {
  long long id;
  size_t k;
  double width;
  bool near_cusp;
};

// The floor of the sizes along face f's narrow parts, `wide` being its width (2 area / perimeter):
// `floor` where it is pinched, somewhere away from a cusp narrower than kPinchFraction of that, and
// only over short stretches: along every edge, each run of samples that narrow takes at most
// kPinchSegments segments at kWidthFactor times its width, down to the floor. Where a run is
// longer (a narrow arm of a plate), the lowest floor at which it takes kPinchSegments: a floor that
// keeps it to a bounded count refines its narrow neighbours no more than a pinch does, and leaves
// triangles across it better than `ceiling`. `ceiling` where the face has no such run, or is under
// h / kNeedleRatio wide (narrow all along, sized as a needle).
double narrow_floor(double wide, double h, double floor, double ceiling, const std::vector<Across>& across,
                    const std::map<long long, SizeProfile>& profiles) {
  const double pinch = kPinchFraction * wide;
  if (!(wide >= h / kNeedleRatio) || !(floor < ceiling)) return ceiling;
  std::map<long long, std::vector<std::pair<size_t, double>>> narrow;
  for (const Across& x : across)
    if (!x.near_cusp && x.width < pinch) narrow[x.id].emplace_back(x.k, x.width);
  if (narrow.empty()) return ceiling;
  for (auto& [id, ks] : narrow) std::sort(ks.begin(), ks.end());
  // The segments of the longest run at floor f.
  auto longest_run = [&](double f) {
    double most = 0;
    for (const auto& [id, ks] : narrow) {
      const std::vector<double>& arc = profiles.at(id).s;
      double segments = 0;
      for (size_t i = 1; i < ks.size(); ++i) {
        if (ks[i].first > ks[i - 1].first + 1) {
          segments = 0;
          continue;
        }
        segments += (arc[ks[i].first] - arc[ks[i - 1].first]) / std::max(f, kWidthFactor * 0.5 * (ks[i].second + ks[i - 1].second));
        most = std::max(most, segments);
      }
    }
    return most;
  };
  if (longest_run(floor) <= kPinchSegments) return floor;
  if (longest_run(ceiling) > kPinchSegments) return ceiling;
  double lo = floor, hi = ceiling;  // too many segments at lo, few enough at hi
  for (int i = 0; i < 40; ++i) {
    const double mid = std::sqrt(lo * hi);
    (longest_run(mid) > kPinchSegments ? lo : hi) = mid;
  }
  return hi;
}

// Lowers the sizes along the edges where a face is narrower than them, to kWidthFactor times its
// width: down to narrow_floor's floor (h / kPinchFloorFraction on a pinched face, at most
// h / kNarrowestCornerFraction); not at all in a cusp's wedge. Decided per face: a floor that
// changed from sample to sample would make the sizes along its edges rise and fall.
void lower_across_faces(const CadModel& model, double h, const std::vector<Cusp>& cusps, std::map<long long, SizeProfile>& profiles) {
  const double floor = h / kPinchFloorFraction, segments = needle_segments(model, h);
  std::vector<Across> across;
  for (const CadFace& f : model.faces) {
    if (!f.error.empty()) continue;
    const double wide = face_width(f);
    const double corner_floor = std::min(h / kNarrowestCornerFraction, wide < h / kNeedleRatio ? needle_floor(f, h, segments) : h);
    across.clear();
    lower_by_width(f, h / kWidthFactor, kCoincident * model.bbox_diagonal, [&](long long id, size_t k, double width, const std::array<double, 3>& p) {
      bool near_cusp = false;
      for (const Cusp& c : cusps) {
        const double d = distance(p.data(), c.point.data());
        near_cusp = near_cusp || (d < kCuspReach * h && width >= kWedgeShare * d * std::sin(c.degrees * kDegree));
      }
      across.push_back({id, k, width, near_cusp});
    }, profiles);
    const double narrowest = narrow_floor(wide, h, floor, corner_floor, across, profiles);
    for (const Across& x : across) {
      if (x.near_cusp) continue;
      double& v = profiles.at(x.id).v[x.k];
      v = std::min(v, std::max(narrowest, kWidthFactor * x.width));
    }
  }
}

// A fan grows by at least this fraction per segment: a cusp under about 1.1 degrees (two edges
// leaving a vertex almost tangent) would otherwise take thousands of segments, from h / 300 up.
constexpr double kFanLeastGrowth = 0.05;

// Whether a cusp is a corner between two sides: not a seam met by itself (a loop going along a
// seam and back, a corner of 0 degrees with no wedge to fan).
bool wedge(const Cusp& c) { return c.edges[0] < 0 || c.edges[0] != c.edges[1]; }

// The sharpest cusp at point p (within tol), in degrees; 0 if none.
double cusp_degrees(const std::vector<Cusp>& cusps, const double* p, double tol) {
  double sharpest = 0;
  for (const Cusp& c : cusps)
    if (wedge(c) && distance(p, c.point.data()) <= tol && c.degrees > 0 && (sharpest == 0 || c.degrees < sharpest)) sharpest = c.degrees;
  return sharpest;
}

// Replaces the nodes (arc lengths t, from 0 to the edge's length) near the edge's start by a fan
// from a cusp of `degrees`. From the cusp the first segment is `first` (the same on both edges of the
// cusp: the vertex's size). The cusp is the edge's start, or, `continued`, lies one segment behind
// it: the side's first edge was that single segment, of length `first`, and this edge goes on from
// it. Then each segment is kWidthFactor times the width across the corner where it
// starts (the triangles across it about right triangles of legs 2.5 : 1, Lo lambda 0.6; legs
// 1.5 : 1 took U_Joint_2 from 21k to 32k triangles and left nist_ctc_02 worse where its fan meets
// the other nodes), until that is no shorter than the segments there were, up to `reach` along the
// edge (half of it when a cusp ends it at both ends). The old nodes from half a segment past the
// fan on stay (moving them along to follow the fan lowered min lambda on other models:
// kicad_Inductor 0.380 -> 0.216 at 1/40).
void fan_from_start(std::vector<double>& t, double first, bool continued, double degrees, double reach) {
  const double length = t.back(), offset = continued ? first : 0;
  const double grow = std::max(kFanLeastGrowth, kWidthFactor * 2 * std::sin(0.5 * degrees * kDegree));
  if (t.size() < 3 || !(first > 0) || (!continued && !(first < 0.5 * length))) return;
  auto spacing = [&](double s) {
    const size_t k = static_cast<size_t>(std::upper_bound(t.begin(), t.end(), s) - t.begin());
    return k < t.size() && k > 0 ? t[k] - t[k - 1] : t[1] - t[0];
  };
  std::vector<double> fan = {0.0};
  double s = 0;
  if (!continued) fan.push_back(s = first);
  for (;;) {
    const double step = grow * (offset + s);
    if (step >= spacing(s) || s + step >= reach - 0.5 * step) break;
    fan.push_back(s += step);
  }
  if (fan.size() <= (continued ? 1u : 2u)) return;
  const double keep_from = s + 0.5 * spacing(s);
  for (double x : t)
    if (x >= keep_from) fan.push_back(x);
  if (fan.back() != length) fan.push_back(length);
  t = std::move(fan);
}

// fan_from_start from the edge's end instead.
void fan_from_end(std::vector<double>& t, double first, bool continued, double degrees, double reach) {
  const double length = t.back();
  for (double& x : t) x = length - x;
  std::reverse(t.begin(), t.end());
  fan_from_start(t, first, continued, degrees, reach);
  for (double& x : t) x = length - x;
  std::reverse(t.begin(), t.end());
}

// Where a side of a cusp is a single segment, the fan goes on along the edge of the face's loop
// that follows it (`Cusp::beyond`), from its shared vertex, as if that edge began at the cusp.
void fan_beyond_cusps(const std::map<long long, Chain>& chains, const std::vector<Cusp>& cusps, double tol,
                      std::map<long long, std::vector<double>>& out) {
  for (const Cusp& c : cusps)
    for (size_t side = 0; side < 2 && wedge(c); ++side) {
      const auto e = chains.find(c.edges[side]), n = chains.find(c.beyond[side]);
      if (e == chains.end() || n == chains.end() || e == n || n->second.closed || out.at(e->first).size() != 2) continue;
      const Chain& ce = e->second;
      const bool tip_at_start = distance(&ce.face->xyz[3 * static_cast<size_t>(ce.edge->vertices.front())], c.point.data()) <= tol;
      const int far = tip_at_start ? ce.v1 : ce.v0;
      std::vector<double>& t = out.at(n->first);
      const double first = out.at(e->first).back();
      if (n->second.v0 == far) fan_from_start(t, first, true, c.degrees, t.back());
      else if (n->second.v1 == far) fan_from_end(t, first, true, c.degrees, t.back());
    }
}

// The arc lengths of each edge's nodes with local sizes: each edge's size (`Chain::size`) lowered
// where a face that has it is narrower than its segments (lower_across_faces; the narrowest places
// between chain vertices sampled too, add_pinch_samples) and at each model vertex to the smallest
// segment of the edges meeting there, then graded by g per unit length away from those.
std::map<long long, std::vector<double>> graded_targets(const CadModel& model, double h, const std::map<long long, Chain>& chains,
                                                        size_t n_vertices, double g, const std::vector<Cusp>& cusps) {
  std::map<long long, std::vector<double>> pinches;
  for (const CadFace& f : model.faces)
    if (f.error.empty()) add_pinch_samples(f, h / kWidthFactor, kCoincident * model.bbox_diagonal, pinches);
  std::map<long long, SizeProfile> profiles;
  for (const auto& [id, c] : chains) {
    SizeProfile p;
    p.s = sample_arcs(chain_arcs(*c.face, *c.edge), h / 4);
    if (const auto it = pinches.find(id); it != pinches.end()) {
      const double length = p.s.back();  // not p.s.back() in the loop: that is the last sample added
      for (double s : it->second)
        if (s > 0 && s < length) p.s.push_back(s);
      std::sort(p.s.begin(), p.s.end());
      p.s.erase(std::unique(p.s.begin(), p.s.end()), p.s.end());
    }
    p.v.assign(p.s.size(), c.size);
    lower_by_turning(*c.face, *c.edge, h / kSmallestRadiusFraction, p);
    profiles.emplace(id, std::move(p));
  }
  lower_across_faces(model, h, cusps, profiles);
  std::vector<double> vertex_size(n_vertices, 1e300);
  for (auto& [id, p] : profiles) {
    const Chain& c = chains.at(id);
    grade(p.s, p.v, g);
    const double u = c.length / static_cast<double>(uniform_count(c.length, c.size, c.closed));
    for (auto [v, end] : {std::pair<int, double>{c.v0, p.v.front()}, {c.v1, p.v.back()}})
      vertex_size[static_cast<size_t>(v)] = std::min({vertex_size[static_cast<size_t>(v)], u, end});
  }
  std::map<long long, std::vector<double>> out;
  const double tol = kCoincident * model.bbox_diagonal;
  for (auto& [id, p] : profiles) {
    const Chain& c = chains.at(id);
    const std::vector<double> cap = p.v;
    p.v.front() = std::min(p.v.front(), vertex_size[static_cast<size_t>(c.v0)]);
    p.v.back() = std::min(p.v.back(), vertex_size[static_cast<size_t>(c.v1)]);
    grade(p.s, p.v, g);
    add_peaks(p.s, p.v, cap, g);
    const SampledSize sz(p.s, p.v);
    const long long n = std::max<long long>(c.closed ? 3 : 1, std::llround(sz.total()));
    std::vector<double>& t = out[id];
    for (long long k = 0; k <= n; ++k) t.push_back(sz.inverse(sz.total() * static_cast<double>(k) / static_cast<double>(n)));
    if (c.closed || t.size() < 2) continue;
    const double theta0 = cusp_degrees(cusps, &c.face->xyz[3 * static_cast<size_t>(c.edge->vertices.front())], tol);
    const double theta1 = cusp_degrees(cusps, &c.face->xyz[3 * static_cast<size_t>(c.edge->vertices.back())], tol);
    const double reach = theta0 > 0 && theta1 > 0 ? 0.5 * t.back() : t.back();
    if (theta0 > 0) fan_from_start(t, vertex_size[static_cast<size_t>(c.v0)], false, theta0, reach);
    if (theta1 > 0) fan_from_end(t, vertex_size[static_cast<size_t>(c.v1)], false, theta1, reach);
  }
  fan_beyond_cusps(chains, cusps, tol, out);
  return out;
}

}  // namespace

double chain_length(const CadFace& f, const CadEdge& e) {
  double length = 0;
  for (size_t i = 0; i + 1 < e.vertices.size(); ++i)
    length += distance(&f.xyz[3 * static_cast<size_t>(e.vertices[i])], &f.xyz[3 * static_cast<size_t>(e.vertices[i + 1])]);
  return length;
}

// The face's smaller radius of curvature, from its facets: across each facet edge inside the face,
// the mean distance of the two opposite corners from the edge over the angle between the facets'
// normals (on a cylinder's facets, its radius). A low quantile by area, not the minimum nor a
// quantile by count: a tessellation of a freeform face has needle facets along its edges whose
// heights, over any angle, give radii a thousandth of the surface's, and there may be many of them.
// Infinite on a flat face.
double curvature_radius(const CadFace& f) {
  const size_t n = f.triangles.size() / 3;
  auto point = [&](int32_t v) { return &f.xyz[3 * static_cast<size_t>(v)]; };
  auto normal = [&](size_t t) {
    const double *a = point(f.triangles[3 * t]), *b = point(f.triangles[3 * t + 1]), *c = point(f.triangles[3 * t + 2]);
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    std::array<double, 3> m{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    const double len = std::sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
    for (double& x : m) x = len > 0 ? x / len : 0;
    return m;
  };
  // Distance of p from the line through a and b.
  auto off_line = [](const double* p, const double* a, const double* b) {
    const double e[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
    const double c[3] = {e[1] * w[2] - e[2] * w[1], e[2] * w[0] - e[0] * w[2], e[0] * w[1] - e[1] * w[0]};
    const double le = std::sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
    return le > 0 ? std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]) / le : 0.0;
  };
  std::unordered_map<unsigned long long, size_t> first;  // directed edge -> the corner opposite it
  std::vector<std::pair<double, double>> radii;  // (radius, twice the two facets' area)
  for (size_t t = 0; t < n; ++t)
    for (size_t c = 0; c < 3; ++c) {
      const int32_t va = f.triangles[3 * t + c], vb = f.triangles[3 * t + (c + 1) % 3];
      const auto a = static_cast<unsigned long long>(static_cast<uint32_t>(va)), b = static_cast<unsigned long long>(static_cast<uint32_t>(vb));
      const auto it = first.find(b << 32 | a);
      if (it == first.end()) {
        first.emplace(a << 32 | b, 3 * t + (c + 2) % 3);
        continue;
      }
      const auto n0 = normal(it->second / 3), n1 = normal(t);
      const double angle = std::acos(std::clamp(n0[0] * n1[0] + n0[1] * n1[1] + n0[2] * n1[2], -1.0, 1.0));
      if (!(angle > 1e-3)) continue;
      const double h0 = off_line(point(f.triangles[it->second]), point(va), point(vb));
      const double h1 = off_line(point(f.triangles[3 * t + (c + 2) % 3]), point(va), point(vb));
      radii.emplace_back(0.5 * (h0 + h1) / angle, distance(point(va), point(vb)) * (h0 + h1));
    }
  if (radii.size() < 4) return std::numeric_limits<double>::infinity();
  std::sort(radii.begin(), radii.end());
  double total = 0;
  for (const auto& r : radii) total += r.second;
  double below = 0;
  for (const auto& [r, area] : radii)
    if ((below += area) >= 0.1 * total) return r;
  return radii.back().first;
}

// Whether all the face's facet normals lie within kLittleTurn of their area-weighted mean: a fillet
// along a line does, a half tube, a fillet round a hole or a sphere does not.
bool turns_little(const CadFace& f) {
  std::vector<std::array<double, 3>> normals;
  std::array<double, 3> mean{0, 0, 0};
  for (size_t t = 0; t + 2 < f.triangles.size(); t += 3) {
    const double* a = &f.xyz[3 * static_cast<size_t>(f.triangles[t])];
    const double* b = &f.xyz[3 * static_cast<size_t>(f.triangles[t + 1])];
    const double* c = &f.xyz[3 * static_cast<size_t>(f.triangles[t + 2])];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const std::array<double, 3> m{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    for (int k = 0; k < 3; ++k) mean[k] += m[k];  // the cross product's length is twice the area
    normals.push_back(m);
  }
  const double lm = std::sqrt(mean[0] * mean[0] + mean[1] * mean[1] + mean[2] * mean[2]);
  if (!(lm > 0)) return false;
  const double cos_limit = std::cos(kLittleTurn);
  for (const auto& n : normals) {
    const double ln = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (ln > 0 && (n[0] * mean[0] + n[1] * mean[1] + n[2] * mean[2]) < cos_limit * ln * lm) return false;
  }
  return true;
}

double face_area(const CadFace& f) {
  double area = 0;
  for (size_t t = 0; t + 2 < f.triangles.size(); t += 3) {
    const double* a = &f.xyz[3 * static_cast<size_t>(f.triangles[t])];
    const double* b = &f.xyz[3 * static_cast<size_t>(f.triangles[t + 1])];
    const double* c = &f.xyz[3 * static_cast<size_t>(f.triangles[t + 2])];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double x = u[1] * v[2] - u[2] * v[1], y = u[2] * v[0] - u[0] * v[2], z = u[0] * v[1] - u[1] * v[0];
    area += 0.5 * std::sqrt(x * x + y * y + z * z);
  }
  return area;
}

double face_width(const CadFace& f) {
  const double perimeter = face_perimeter(f);
  return perimeter > 0 ? 2 * face_area(f) / perimeter : std::nan("");
}

EdgeNodes uniform_edge_nodes(const CadFace& face, const CadEdge& edge, long long segments) {
  segments = std::max(1LL, segments);
  const double length = chain_length(face, edge);
  std::vector<double> targets;
  for (long long k = 0; k <= segments; ++k) targets.push_back(length * static_cast<double>(k) / static_cast<double>(segments));
  return place(face, edge, targets);
}

EdgeNodes recount_edge_nodes(const CadFace& face, const CadEdge& edge, const EdgeNodes& nodes, long long segments) {
  if (nodes.segments() < 1 || segments < 1) return uniform_edge_nodes(face, edge, std::max(1LL, segments));
  const auto n = static_cast<size_t>(nodes.segments());
  const double length = chain_length(face, edge);
  // The old nodes' arc lengths: their chords, scaled to the chain's length (the nodes lie on it).
  std::vector<double> s(n + 1, 0.0);
  for (size_t k = 1; k <= n; ++k) s[k] = s[k - 1] + distance(&nodes.xyz[3 * (k - 1)], &nodes.xyz[3 * k]);
  if (!(s[n] > 0)) return uniform_edge_nodes(face, edge, segments);
  std::vector<double> targets;
  for (long long j = 0; j <= segments; ++j) {
    const double x = static_cast<double>(j) * static_cast<double>(n) / static_cast<double>(segments);
    const size_t k = std::min(n - 1, static_cast<size_t>(x));
    const double t = x - static_cast<double>(k);
    targets.push_back(length * (s[k] + t * (s[k + 1] - s[k])) / s[n]);
  }
  targets.front() = 0, targets.back() = length;
  return place(face, edge, targets);
}

std::vector<double> local_face_sizes(const CadModel& model, double h) {
  std::vector<double> sizes(model.faces.size(), h);
  const double segments = needle_segments(model, h);
  for (size_t k = 0; k < model.faces.size(); ++k) {
    const CadFace& f = model.faces[k];
    if (!f.error.empty()) continue;
    const double w = face_width(f), width = std::isnan(w) ? h : w;
    // A face that wraps round its smaller radius r (a tube, a sphere) gets about six segments
    // around a full turn (a hexagon's side is its radius): coarser, the chords of a thin tube fold
    // onto each other. A face that turns less (a fillet, a blend) gets sqrt(r h): its chords then
    // deviate from it by at most h / 8, as an element of size h does on a face of radius h; r there
    // multiplied the triangles of filleted models several times over for no better shape. Small
    // holes keep their six segments through their closed edges (discretise_model_edges).
    // Curvature may ask for smaller elements than narrowness: a tube needs its six segments around
    // whatever its length, while a long narrow strip cannot ask for millions along it.
    const double r = curvature_radius(f);
    const double curved = width < kWrapWidth * r && turns_little(f) ? std::sqrt(r * h) : r;
    const double narrow = std::max(kWidthFactor * width, needle_floor(f, h, segments));
    const double length = std::isfinite(r) && r > 0 ? face_area(f) / (2 * 3.14159265358979 * r) : h;  // of a tube of radius r
    const bool wraps = std::isfinite(r) && curved == r && length <= h &&
                       std::any_of(f.edges.begin(), f.edges.end(), [](const CadEdge& e) { return e.seam; });
    const double smallest = wraps ? std::min(h / kSmallestRadiusFraction, 2 * 3.14159265358979 * r / kFewestAround)
                                  : h / kSmallestRadiusFraction;
    sizes[k] = std::min({std::clamp(curved, smallest, h), narrow, h});
  }
  return sizes;
}

std::map<long long, EdgeNodes> discretise_model_edges(const CadModel& model, double h, const std::vector<double>& face_sizes,
                                                      double gradation, const std::vector<Cusp>& cusps) {
  std::map<long long, double> edge_size;
  for (size_t k = 0; k < model.faces.size(); ++k) {
    const double hf = k < face_sizes.size() ? face_sizes[k] : h;
    for (const CadEdge& e : model.faces[k].edges) {
      auto [it, fresh] = edge_size.emplace(e.id, hf);
      if (!fresh) it->second = std::min(it->second, hf);
    }
  }
  // Each edge once, from the first face that has it.
  std::map<long long, Chain> chains;
  VertexIds vertices(1e-7 * model.bbox_diagonal);
  for (const CadFace& f : model.faces) {
    if (!f.error.empty()) continue;
    for (const CadEdge& e : f.edges) {
      if (e.degenerated || e.vertices.size() < 2 || chains.count(e.id)) continue;
      const int v0 = vertices.of(&f.xyz[3 * static_cast<size_t>(e.vertices.front())]);
      const int v1 = vertices.of(&f.xyz[3 * static_cast<size_t>(e.vertices.back())]);
      chains.emplace(e.id, Chain{&f, &e, chain_length(f, e), edge_size.at(e.id), e.vertices.front() == e.vertices.back(), v0, v1});
    }
  }
  std::map<long long, std::vector<double>> targets;
  if (gradation > 0) {
    targets = graded_targets(model, h, chains, vertices.size(), gradation, cusps);
  } else {
    for (const auto& [id, c] : chains) {
      const long long n = uniform_count(c.length, c.size, c.closed);
      for (long long k = 0; k <= n; ++k) targets[id].push_back(c.length * static_cast<double>(k) / static_cast<double>(n));
    }
  }
  at_least_two_per_half_turn(chains, targets);
  at_least_three_per_loop(model, targets);
  std::map<long long, EdgeNodes> nodes;
  for (const auto& [id, c] : chains) nodes.emplace(id, place(*c.face, *c.edge, targets.at(id)));
  return nodes;
}

}  // namespace wefm_cad
