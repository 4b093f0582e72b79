#include "virtual_faces.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <set>
#include <unordered_map>

#include "cad_edge_nodes.hpp"
#include "cad_wefm.hpp"
#include "coincident_faces.hpp"
#include "conformal_first.hpp"
#include "face_corners.hpp"
#include "owned.hpp"

namespace wefm_cli {

namespace {

// A face narrower than h / this (2 area / perimeter) is merged. A face narrower than h / kNeedleRatio
// keeps slivers on its own: over the 59 cad-more models at h = 1/40 of the diagonal without merging,
// 91 of the 132 had a triangle with Lo lambda below 0.3. Wider faces mesh well on their own (18 of
// 2,462 between h / 100 and h / 20 had one), but only at a cost: their local size and the edges'
// shrinking towards them (down to h / 32 across a strip, cad_edge_nodes) refine their long edges, and the
// neighbours grade back up from those. Merging the faces up to h / 30 wide with their smoothest
// neighbour halves that (docs/PERFORMANCE.md); up to h / 20 it also merged the touching faces of an
// assembly's volumes differently and folded them onto each other at the weld.
constexpr double kNarrowRatio = 30;
constexpr double kNeedleRatio = 100;
// A narrow face is never merged across an edge where the facet normals of the two faces turn by
// more than this: a 45-degree chamfer merges with either face, the right-angle edge of a box does
// not. A triangle spanning a strip of width w < h / 30 at such a kink leaves the surface by at most
// w sin(25 deg) < h / 70.
constexpr double kSharpDegrees = 50;
// A face narrower than h / kSliverRatio merges across a sharper edge too, a step's right angle
// included: a triangle spanning it leaves the surface by at most its width, under h / 300. Kept, it
// meshes with slivers or takes hundreds of segments along its length (nodeocc_kuka's 0.00065-wide
// step face 562 at h = 53: min Lo lambda 0.005). Wider needles keep kSharpDegrees: at 1/20 of the
// diagonal pyocc_11752 and kicad_Inductor have hundreds of thread faces between h / 300 and h / 100
// wide, and merged across their sharp edges they took 95 s and 11 s in trials for no better minimum.
constexpr double kSliverRatio = 300;
// The most such a face turns to the neighbour it merges with: only a face folding back onto it is
// left out. Facet normals err by up to BRepMesh's angular deflection (0.5 rad), so a right angle can
// measure up to about 120 degrees.
constexpr double kNeedleSharpDegrees = 150;
// A face merged for a sharp corner is wide: triangles of size h straddle the edge left out, and
// leave the surface by up to h / 2 sin(turn / 2), h / 8 at this turn: the chord deviation that the
// local size allows on a curved face (h at most its radius, h^2 / 8r).
constexpr double kCornerSharpDegrees = 30;
// A face with a corner sharper than this (degrees, inside the face) is merged with the neighbour
// across one of the corner's edges: a triangle in a corner of angle t has Lo lambda at most
// 2 sqrt(3) sin t / (2 + 4 sin^2(t / 2)), 0.30 at 10.5 degrees, whatever the sizes.
constexpr double kSharpCornerDegrees = 12;
// The quality a merge is for (issue 28: min Lo lambda 0.3 on every model).
constexpr double kLambdaFloor = 0.3;
// A merged face that keeps a corner under kFloorCornerDegrees (virtual_faces.hpp) cannot reach
// kLambdaFloor, so it is not meshed to find out.

using Normal = std::array<double, 3>;

const double* at(const wefm_cad::CadFace& f, int32_t v) { return &f.xyz[3 * static_cast<size_t>(v)]; }

double distance(const double* a, const double* b) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

uint64_t pair_key(int32_t a, int32_t b) {
  if (a > b) std::swap(a, b);
  return (static_cast<uint64_t>(static_cast<uint32_t>(a)) << 32) | static_cast<uint32_t>(b);
}

constexpr size_t kNoFacet = static_cast<size_t>(-1);

// Along `chain`, in one pass over f's facets: per segment (a pair of consecutive vertices) the first
// facet having it as an edge, or kNoFacet; per vertex the unit sum of the normals of the facets
// around it, each weighted by its area. Only the chain's segments and vertices are kept: a face
// absorbs narrow faces one after the other, and each time its chains are looked up again.
struct ChainFacets {
  std::unordered_map<uint64_t, size_t> segment_facet;
  std::unordered_map<int32_t, Normal> vertex_normal;
};

ChainFacets facets_along(const wefm_cad::CadFace& f, const std::vector<int32_t>& chain) {
  ChainFacets out;
  for (size_t k = 0; k + 1 < chain.size(); ++k) out.segment_facet.emplace(pair_key(chain[k], chain[k + 1]), kNoFacet);
  for (int32_t v : chain) out.vertex_normal.emplace(v, Normal{0, 0, 0});
  for (size_t t = 0; 3 * t + 2 < f.triangles.size(); ++t) {
    bool on_chain = false;
    for (size_t c = 0; c < 3; ++c) {
      const auto it = out.segment_facet.find(pair_key(f.triangles[3 * t + c], f.triangles[3 * t + (c + 1) % 3]));
      if (it != out.segment_facet.end() && it->second == kNoFacet) it->second = t;
      on_chain = on_chain || out.vertex_normal.count(f.triangles[3 * t + c]);
    }
    if (!on_chain) continue;
    const Normal n = facet_cross(f, t);
    for (size_t c = 0; c < 3; ++c) {
      const auto it = out.vertex_normal.find(f.triangles[3 * t + c]);
      if (it != out.vertex_normal.end())
        for (size_t d = 0; d < 3; ++d) it->second[d] += n[d];
    }
  }
  for (auto& [v, n] : out.vertex_normal) {
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (double& x : n) x = len > 0 ? x / len : 0;
  }
  return out;
}

// How much the surface turns across the chain of edge index ea of a and eb of b (the same model
// edge), in degrees, measured two ways: the largest angle between the two faces' facet normals on
// the chain's segments, and between their vertex normals (area-weighted over the facets around the
// vertex) at its vertices; 180 both when a segment has no facet on one side.
struct Turn {
  double facets = 0, vertices = 0;
};

// A facet's normal departs from the surface's by up to BRepMesh's angular deflection (0.5 rad by
// default), most on the sliver facets at a sharp corner, and a vertex normal errs elsewhere (at a
// chain's ends, where a face's facets fan out): either can take a smooth edge for a sharp one. On
// coarser facets (a deflection of 0.003 of the diagonal) gmsh_component8's faces 10 to 14 (corners of
// 6.4 degrees) measured over 30 degrees across their edges to face 1 by facet normals, under 30 by
// vertex normals, and stayed unmerged with min Lo lambda 0.187 (0.786 merged).
Turn dihedral(const wefm_cad::CadFace& a, size_t ea, const wefm_cad::CadFace& b, size_t eb, bool reversed) {
  const auto& ca = a.edges[ea].vertices;
  const auto& cb = b.edges[eb].vertices;
  const auto fa = facets_along(a, ca), fb = facets_along(b, cb);
  const size_t n = ca.size();
  auto angle = [](const Normal& x, const Normal& y) {
    return degrees(std::acos(std::clamp(x[0] * y[0] + x[1] * y[1] + x[2] * y[2], -1.0, 1.0)));
  };
  Turn turn;
  for (size_t k = 0; k + 1 < n; ++k) {
    const size_t kb = reversed ? n - 1 - k : k, kb1 = reversed ? n - 2 - k : k + 1;
    const auto ia = fa.segment_facet.find(pair_key(ca[k], ca[k + 1])), ib = fb.segment_facet.find(pair_key(cb[kb], cb[kb1]));
    if (ia == fa.segment_facet.end() || ib == fb.segment_facet.end() || ia->second == kNoFacet || ib->second == kNoFacet)
      return Turn{180, 180};
    turn.facets = std::max(turn.facets, angle(facet_normal(a, ia->second), facet_normal(b, ib->second)));
  }
  for (size_t k = 0; k < n; ++k)
    turn.vertices = std::max(turn.vertices, angle(fa.vertex_normal.at(ca[k]), fb.vertex_normal.at(cb[reversed ? n - 1 - k : k])));
  return turn;
}

// Whether b's chain of edge eb runs along a's chain of edge ea (same points within tol), forwards
// (reversed = false) or backwards.
bool same_chain(const wefm_cad::CadFace& a, size_t ea, const wefm_cad::CadFace& b, size_t eb, double tol, bool& reversed) {
  const auto& ca = a.edges[ea].vertices;
  const auto& cb = b.edges[eb].vertices;
  if (ca.size() != cb.size() || ca.size() < 2) return false;
  for (bool rev : {false, true}) {
    bool ok = true;
    for (size_t k = 0; k < ca.size() && ok; ++k) ok = distance(at(a, ca[k]), at(b, cb[rev ? ca.size() - 1 - k : k])) <= tol;
    if (ok) {
      reversed = rev;
      return true;
    }
  }
  return false;
}

// Where the uses of the shared edges sit: the one loop holding all of them, rotated so they come
// last, as one run. False when they are spread over loops, not contiguous or used more than once.
bool shared_run(const wefm_cad::CadFace& f, const std::set<size_t>& shared, int& loop, std::vector<wefm_cad::CadEdgeUse>& rest,
                std::vector<wefm_cad::CadEdgeUse>& run) {
  loop = -1;
  for (size_t l = 0; l < f.loops.size(); ++l)
    for (const auto& u : f.loops[l])
      if (shared.count(static_cast<size_t>(u.edge))) {
        if (loop >= 0 && loop != static_cast<int>(l)) return false;
        loop = static_cast<int>(l);
      }
  if (loop < 0) return false;
  const auto& uses = f.loops[static_cast<size_t>(loop)];
  const size_t n = uses.size();
  auto in = [&](size_t k) { return shared.count(static_cast<size_t>(uses[k % n].edge)) > 0; };
  size_t start = 0;  // first use of the run: a shared use after an unshared one
  for (size_t k = 0; k < n; ++k)
    if (in(k) && !in(k + n - 1)) start = k;
  rest.clear(), run.clear();
  for (size_t k = 0; k < n; ++k) {
    const auto& u = uses[(start + k) % n];
    (in(start + k) ? run : rest).push_back(u);
  }
  // Contiguous: the run is the first run.size() uses from start.
  for (size_t k = 0; k < run.size(); ++k)
    if (!in(start + k)) return false;
  return run.size() == shared.size();
}

// Whether every facet edge is used at most twice, once each way (one consistent orientation).
bool manifold(const std::vector<int32_t>& tris) {
  std::set<std::pair<int32_t, int32_t>> directed;
  for (size_t t = 0; t + 2 < tris.size(); t += 3)
    for (size_t c = 0; c < 3; ++c)
      if (!directed.insert({tris[t + c], tris[t + (c + 1) % 3]}).second) return false;
  return true;
}

// One trial of a merged face: flattened at `s` (NaN: the library's default) and meshed at size h.
// `retry` is set where a conformal flattening was unusable (a negative score) or the mesher refused
// it: mesh-model flattens such a face again at the default s, and so does the trial.
bool trial(const wefm_cad::CadFace& f, double h, double s, std::string& why, bool& retry) {
  retry = false;
  wefm_face* raw = nullptr;
  if (wefm_face_create(&raw) != WEFM_OK) return why = "out of memory", false;
  std::unique_ptr<wefm_face, FaceDeleter> handle(raw);
  std::string error;
  wefm_options o;
  wefm_options_init(&o);
  if (std::isfinite(s)) o.s = s;
  if (wefm_cad::set_face_from_cad(raw, f, error) != WEFM_OK || wefm_face_set_options(raw, &o) != WEFM_OK || wefm_face_build(raw) != WEFM_OK)
    return why = "topology: " + (error.empty() ? std::string(wefm_face_last_error(raw)) : error), false;
  const wefm_status st = wefm_face_solve(raw);
  int32_t has = 0;
  wefm_face_has_result(raw, &has);
  const bool conformal = std::isfinite(s);
  if (st != WEFM_OK && !(st == WEFM_ERROR_NOT_CONVERGED && has))
    return retry = conformal, why = std::string("flatten: ") + wefm_face_last_error(raw), false;
  wefm_report rep;
  wefm_report_init(&rep, sizeof rep);
  if (conformal && wefm_face_get_report(raw, &rep) == WEFM_OK)
    if (const char* unusable = conformal_unusable(rep)) return retry = true, why = unusable, false;
  wefm_mesh_options options;
  wefm_mesh_options_init(&options, sizeof options);
  options.size = h;
  wefm_domain_mesh* dm = nullptr;
  const wefm_status ms = wefm_face_mesh_domain(raw, &options, &dm);
  OwnedDomainMesh owned(dm);
  if (ms != WEFM_OK) return retry = conformal, why = std::string("mesh: ") + wefm_face_last_error(raw), false;
  // A merge is made for the quality floor: one that does not reach it on its own (the narrow face's
  // short end edges left in a corner of the merged face) is not made.
  wefm_mesh_report report;
  wefm_mesh_report_init(&report, sizeof report);
  if (wefm_domain_mesh_get_report(dm, &report) == WEFM_OK && report.lambda_min < kLambdaFloor) {
    char text[96];
    std::snprintf(text, sizeof text, "the merged face meshes with min lambda %.3f", report.lambda_min);
    return why = text, false;
  }
  return true;
}

// Whether the library takes the merged face: its topology (loops close, edges are facet edges,
// one outer loop), and its flattening, conformal first as mesh-model's (then at the default s),
// meshes at size h (a strip folded at a kink can flatten onto itself: "the domain's boundary
// intersects itself") with min Lo lambda kLambdaFloor.
bool library_takes(const wefm_cad::CadFace& f, double h, std::string& why) {
  bool retry = false;
  if (trial(f, h, kConformalS, why, retry)) return true;
  return retry && trial(f, h, std::numeric_limits<double>::quiet_NaN(), why, retry);
}

// Merges face b into face a across the edges they share (`shared`: pairs of edge index in a, in b).
// The result keeps a's index and surface type. False + why when the result would not be one valid
// face (see the checks).
bool merge_pair(const wefm_cad::CadFace& a, const wefm_cad::CadFace& b, const std::vector<std::pair<size_t, size_t>>& shared,
                double tol, double h, wefm_cad::CadFace& out, std::string& why) {
  std::vector<int32_t> vmap(b.xyz.size() / 3, -1);
  std::set<size_t> sa, sb;
  std::map<size_t, size_t> a_of_b;
  for (const auto& [ea, eb] : shared) {
    bool reversed = false;
    if (a.edges[ea].seam || b.edges[eb].seam || !same_chain(a, ea, b, eb, tol, reversed)) return why = "shared edge chains differ", false;
    const auto& ca = a.edges[ea].vertices;
    const auto& cb = b.edges[eb].vertices;
    for (size_t k = 0; k < ca.size(); ++k) vmap[static_cast<size_t>(cb[reversed ? ca.size() - 1 - k : k])] = ca[k];
    sa.insert(ea), sb.insert(eb), a_of_b[eb] = ea;
  }
  int la = -1, lb = -1;
  std::vector<wefm_cad::CadEdgeUse> rest_a, run_a, rest_b, run_b;
  if (!shared_run(a, sa, la, rest_a, run_a) || !shared_run(b, sb, lb, rest_b, run_b))
    return why = "shared edges not one run of one loop", false;
  // The face on the left of both: b walks the run backwards, each edge the other way.
  for (size_t k = 0; k < run_a.size(); ++k) {
    const auto& ua = run_a[k];
    const auto& ub = run_b[run_b.size() - 1 - k];
    bool reversed = false;
    same_chain(a, static_cast<size_t>(ua.edge), b, static_cast<size_t>(ub.edge), tol, reversed);
    if (a_of_b[static_cast<size_t>(ub.edge)] != static_cast<size_t>(ua.edge) || (ua.reversed != ub.reversed) == reversed)
      return why = "orientations differ", false;
  }
  const bool a_outer = la == a.outer_loop, b_outer = lb == b.outer_loop;
  if (!a_outer && !b_outer) return why = "shared edges on inner loops of both", false;
  if (a_outer && b_outer && rest_a.empty() && rest_b.empty()) return why = "the merge would have no boundary", false;
  out = wefm_cad::CadFace{};
  out.index = a.index;
  out.surface_type = a.surface_type;
  out.xyz = a.xyz;
  for (size_t v = 0; v < vmap.size(); ++v)
    if (vmap[v] < 0) {
      vmap[v] = static_cast<int32_t>(out.xyz.size() / 3);
      out.xyz.insert(out.xyz.end(), at(b, static_cast<int32_t>(v)), at(b, static_cast<int32_t>(v)) + 3);
    }
  out.triangles = a.triangles;
  for (int32_t v : b.triangles) out.triangles.push_back(vmap[static_cast<size_t>(v)]);
  if (!manifold(out.triangles)) return why = "the merged facets are not a manifold", false;
  std::vector<int32_t> edge_a(a.edges.size(), -1), edge_b(b.edges.size(), -1);
  std::set<long long> ids;
  for (size_t e = 0; e < a.edges.size(); ++e)
    if (!sa.count(e)) edge_a[e] = static_cast<int32_t>(out.edges.size()), out.edges.push_back(a.edges[e]), ids.insert(a.edges[e].id);
  for (size_t e = 0; e < b.edges.size(); ++e) {
    if (sb.count(e)) continue;
    if (ids.count(b.edges[e].id)) return why = "another edge is on both faces", false;
    wefm_cad::CadEdge copy = b.edges[e];
    for (int32_t& v : copy.vertices) v = vmap[static_cast<size_t>(v)];
    edge_b[e] = static_cast<int32_t>(out.edges.size()), out.edges.push_back(copy);
  }
  auto remap = [](std::vector<wefm_cad::CadEdgeUse> uses, const std::vector<int32_t>& m) {
    for (auto& u : uses) u.edge = m[static_cast<size_t>(u.edge)];
    return uses;
  };
  for (size_t l = 0; l < a.loops.size(); ++l) {
    if (static_cast<int>(l) != la) {
      if (static_cast<int>(l) == a.outer_loop) out.outer_loop = static_cast<int>(out.loops.size());
      out.loops.push_back(remap(a.loops[l], edge_a));
      continue;
    }
    auto spliced = remap(rest_a, edge_a);
    for (const auto& u : remap(rest_b, edge_b)) spliced.push_back(u);
    if (spliced.empty()) continue;  // b filled a hole of a exactly
    if (a_outer && b_outer) out.outer_loop = static_cast<int>(out.loops.size());
    out.loops.push_back(spliced);
  }
  for (size_t l = 0; l < b.loops.size(); ++l) {
    if (static_cast<int>(l) == lb) continue;
    if (a_outer && static_cast<int>(l) == b.outer_loop) out.outer_loop = static_cast<int>(out.loops.size());
    out.loops.push_back(remap(b.loops[l], edge_b));
  }
  out.dropped_triangles = a.dropped_triangles + b.dropped_triangles;
  out.triangulation_kept = a.triangulation_kept && b.triangulation_kept;
  if (const auto corners = sharp_corners(out, kFloorCornerDegrees); !corners.empty()) {
    char text[96];
    std::snprintf(text, sizeof text, "the merged face keeps a corner of %.1f degrees", corners[0].degrees);
    return why = text, false;
  }
  return library_takes(out, h, why);
}

// Per model edge id: the faces (by position) whose loops use it, once per use.
std::map<long long, std::vector<size_t>> edge_users(const std::vector<wefm_cad::CadFace>& faces, const std::vector<char>& alive) {
  std::map<long long, std::vector<size_t>> out;
  for (size_t i = 0; i < faces.size(); ++i)
    if (alive[i])
      for (const auto& loop : faces[i].loops)
        for (const auto& u : loop) out[faces[i].edges[static_cast<size_t>(u.edge)].id].push_back(i);
  return out;
}

// Per face (by position): another face lying on it (coincident_faces), or -1.
std::vector<long> twin_faces(const wefm_cad::CadModel& model) {
  const std::vector<size_t> source = coincident_faces(model);
  std::vector<long> twin(source.size(), -1);
  for (size_t j = 0; j < source.size(); ++j)
    if (source[j]) {
      twin[j] = static_cast<long>(source[j] - 1);
      twin[source[j] - 1] = static_cast<long>(j);
    }
  return twin;
}

struct Candidate {
  size_t neighbour;
  std::vector<std::pair<size_t, size_t>> shared;  // edge index in the neighbour, in the narrow face
  std::vector<long long> ids;
  double dihedral;  // by facet normals: the order candidates are tried in
  double turn;      // the smaller of the two measures (Turn): what the limits are checked against
};

// The neighbours of face i it could merge with: across edges used once by i and once by the
// neighbour and by no other face, smoothest first; those across a turn above max_turn left out.
std::vector<Candidate> neighbours(const std::vector<wefm_cad::CadFace>& faces, size_t i,
                                  const std::map<long long, std::vector<size_t>>& users, double tol, double max_turn) {
  std::map<size_t, Candidate> by_face;
  const wefm_cad::CadFace& f = faces[i];
  for (size_t e = 0; e < f.edges.size(); ++e) {
    const auto it = users.find(f.edges[e].id);
    if (it == users.end() || it->second.size() != 2) continue;
    const size_t j = it->second[0] == i ? it->second[1] : it->second[0];
    if (j == i) continue;
    const wefm_cad::CadFace& g = faces[j];
    for (size_t d = 0; d < g.edges.size(); ++d) {
      if (g.edges[d].id != f.edges[e].id) continue;
      bool reversed = false;
      if (!same_chain(g, d, f, e, tol, reversed)) continue;
      Candidate& c = by_face.emplace(j, Candidate{j, {}, {}, 0, 0}).first->second;
      c.shared.push_back({d, e});
      c.ids.push_back(f.edges[e].id);
      const Turn t = dihedral(g, d, f, e, reversed);
      c.dihedral = std::max(c.dihedral, t.facets);
      c.turn = std::max(c.turn, std::min(t.facets, t.vertices));
    }
  }
  std::vector<Candidate> out;
  for (auto& [j, c] : by_face)
    if (c.turn <= max_turn) out.push_back(std::move(c));
  std::sort(out.begin(), out.end(), [](const Candidate& x, const Candidate& y) { return x.dihedral < y.dihedral; });
  return out;
}

}  // namespace

namespace {

// The merges of one model, applied one after the other to its faces.
class Merger {
 public:
  Merger(wefm_cad::CadModel& model, std::vector<double>& sizes, double h)
      : faces_(model.faces), sizes_(sizes), tol_(1e-7 * model.bbox_diagonal), h_(h), alive_(faces_.size(), 1),
        facet_face_(faces_.size()), twin_(twin_faces(model)) {
    users_ = edge_users(faces_, alive_);
  }
  bool alive(size_t i) const { return alive_[i] && faces_[i].error.empty(); }
  const wefm_cad::CadFace& face(size_t i) const { return faces_[i]; }
  bool narrow(size_t i) const { return wefm_cad::face_width(faces_[i]) < h_ / kNarrowRatio; }

  // Merges face i into the smoothest neighbour across one of `across` (model edge ids; empty: any
  // edge) that makes a valid face and is not narrow itself (two needles merged are a needle, its
  // slivers only moved); the merged face keeps the neighbour's size (the smaller of the
  // two multiplied the triangles of a whole model several times over for a few absorbed corners).
  // Records the merge, or why none was made.
  // With `keep_twins`, a face lying on another face neither merges nor absorbs (faces wider than
  // h / kNeedleRatio, which mesh well enough on their own): merged, two faces that lie on each other
  // may no longer be meshed alike, and the weld folds them onto each other.
  bool merge(size_t i, const std::set<long long>& across, double max_turn, double width, const std::string& reason,
             bool keep_twins = false) {
    if (keep_twins && twin_[i] >= 0) {
      vt_.merges.push_back({faces_[i].index, 0, width, 0, {}, reason + "; kept: it lies on face " + std::to_string(faces_[static_cast<size_t>(twin_[i])].index) +
                                                                  ", which is meshed alike only while neither is merged"});
      return false;
    }
    std::string why = "no neighbour across an edge turning by at most " + std::to_string(static_cast<int>(max_turn)) + " degrees";
    for (const Candidate& c : neighbours(faces_, i, users_, tol_, max_turn)) {
      if (!across.empty() && std::none_of(c.ids.begin(), c.ids.end(), [&](long long id) { return across.count(id) > 0; })) continue;
      const size_t j = c.neighbour;
      if (narrow(j)) {
        why = "its smooth neighbours are narrow too";
        continue;
      }
      if (keep_twins && twin_[j] >= 0) {
        why = "its smooth neighbours lie on other faces, meshed alike only while not merged";
        continue;
      }
      wefm_cad::CadFace merged;
      if (!faces_[j].error.empty() || !merge_pair(faces_[j], faces_[i], c.shared, tol_, j < sizes_.size() ? sizes_[j] : h_, merged, why)) continue;
      for (size_t k : {i, j})
        if (facet_face_[k].empty()) facet_face_[k].assign(faces_[k].triangles.size() / 3, faces_[k].index);
      facet_face_[j].insert(facet_face_[j].end(), facet_face_[i].begin(), facet_face_[i].end());
      vt_.merges.push_back({faces_[i].index, faces_[j].index, width, c.turn, c.ids, reason});
      for (const auto& e : faces_[i].edges) {
        auto& list = users_[e.id];
        std::replace(list.begin(), list.end(), i, j);
      }
      for (long long id : c.ids) users_.erase(id);
      faces_[j] = std::move(merged);
      alive_[i] = 0;
      return true;
    }
    vt_.merges.push_back({faces_[i].index, 0, width, 0, {}, reason + "; kept: " + why});
    return false;
  }

  // The merged faces in place of the originals; the merges name the face each ended in.
  VirtualTopology finish() {
    if (std::none_of(vt_.merges.begin(), vt_.merges.end(), [](const FaceMerge& m) { return m.into; })) return std::move(vt_);
    std::map<int, int> final_of;  // a face absorbed into one absorbed later names the last
    for (auto it = vt_.merges.rbegin(); it != vt_.merges.rend(); ++it) {
      if (!it->into) continue;
      const auto f = final_of.find(it->into);
      final_of[it->face] = f == final_of.end() ? it->into : f->second;
    }
    for (FaceMerge& m : vt_.merges)
      if (m.into) m.into = final_of[m.face];
    std::vector<wefm_cad::CadFace> kept;
    std::vector<double> sizes;
    for (size_t i = 0; i < faces_.size(); ++i)
      if (alive_[i]) {
        kept.push_back(std::move(faces_[i]));
        vt_.facet_face.push_back(std::move(facet_face_[i]));
        if (i < sizes_.size()) sizes.push_back(sizes_[i]);
      }
    faces_ = std::move(kept);
    sizes_ = std::move(sizes);
    return std::move(vt_);
  }

 private:
  std::vector<wefm_cad::CadFace>& faces_;
  std::vector<double>& sizes_;
  double tol_, h_;
  std::vector<char> alive_;
  std::vector<std::vector<int>> facet_face_;
  // Faces lying on another face keep their own mesh: merged, the two would no longer be meshed
  // alike and the weld would fold them onto each other.
  std::vector<long> twin_;
  std::map<long long, std::vector<size_t>> users_;
  VirtualTopology vt_;
};

}  // namespace

VirtualTopology merge_narrow_faces(wefm_cad::CadModel& model, double h, std::vector<double>& face_sizes) {
  Merger merger(model, face_sizes, h);
  const size_t n = model.faces.size();
  std::vector<std::pair<double, size_t>> narrow;
  for (size_t i = 0; i < n; ++i) {
    const double w = merger.alive(i) ? wefm_cad::face_width(merger.face(i)) : 0;
    if (w > 0 && w < h / kNarrowRatio) narrow.push_back({w, i});
  }
  std::sort(narrow.begin(), narrow.end());
  for (const auto& [w0, i] : narrow) {
    const double w = merger.alive(i) ? wefm_cad::face_width(merger.face(i)) : 0;  // it may have absorbed a narrower one
    if (!(w < h / kNarrowRatio)) continue;
    char reason[96];
    std::snprintf(reason, sizeof reason, "narrow: width %.3g below h / %g", w, kNarrowRatio);
    merger.merge(i, {}, w < h / kSliverRatio ? kNeedleSharpDegrees : kSharpDegrees, w, reason, w >= h / kNeedleRatio);
  }
  for (size_t i = 0; i < n; ++i) {
    if (!merger.alive(i)) continue;
    const auto corners = sharp_corners(merger.face(i), kSharpCornerDegrees);
    if (corners.empty()) continue;
    char reason[96];
    std::snprintf(reason, sizeof reason, "sharp corner: %.1f degrees below %g", corners[0].degrees, kSharpCornerDegrees);
    merger.merge(i, {corners[0].edges[0], corners[0].edges[1]}, kCornerSharpDegrees, wefm_cad::face_width(merger.face(i)), reason);
  }
  return merger.finish();
}

std::vector<int> triangle_faces(const VirtualTopology& vt, size_t virtual_face, const wefm_cad::CadFace& face,
                                const std::vector<double>& xyz, const std::vector<int32_t>& tris, double h) {
  if (virtual_face >= vt.facet_face.size() || vt.facet_face[virtual_face].empty()) return {};
  const std::vector<int>& source = vt.facet_face[virtual_face];
  // The absorbed faces' facets, with their bounding box grown by h / 2: a triangle's centroid over
  // one of them (its projection inside, at most h / 2 off) goes to that face, any other to `face`.
  std::map<int, std::vector<size_t>> facets;
  for (size_t t = 0; t < source.size(); ++t)
    if (source[t] != face.index) facets[source[t]].push_back(t);
  const double reach = 0.5 * h;
  auto over = [&](const double* p, size_t t) {
    const double *a = at(face, face.triangles[3 * t]), *b = at(face, face.triangles[3 * t + 1]), *c = at(face, face.triangles[3 * t + 2]);
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const double w[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
    const double uu = u[0] * u[0] + u[1] * u[1] + u[2] * u[2], uv = u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
    const double vv = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    const double wu = w[0] * u[0] + w[1] * u[1] + w[2] * u[2], wv = w[0] * v[0] + w[1] * v[1] + w[2] * v[2];
    const double det = uu * vv - uv * uv;
    if (!(det > 0)) return false;
    const double s = (vv * wu - uv * wv) / det, r = (uu * wv - uv * wu) / det;
    if (s < -1e-9 || r < -1e-9 || s + r > 1 + 1e-9) return false;
    const double q[3] = {a[0] + s * u[0] + r * v[0] - p[0], a[1] + s * u[1] + r * v[1] - p[1], a[2] + s * u[2] + r * v[2] - p[2]};
    return std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2]) <= reach;
  };
  std::vector<int> out;
  for (size_t t = 0; t + 2 < tris.size(); t += 3) {
    double c[3];
    for (size_t k = 0; k < 3; ++k)
      c[k] = (xyz[3 * static_cast<size_t>(tris[t]) + k] + xyz[3 * static_cast<size_t>(tris[t + 1]) + k] + xyz[3 * static_cast<size_t>(tris[t + 2]) + k]) / 3;
    int tag = face.index;
    for (const auto& [g, list] : facets)
      if (std::any_of(list.begin(), list.end(), [&](size_t f) { return over(c, f); })) {
        tag = g;
        break;
      }
    out.push_back(tag);
  }
  return out;
}

nlohmann::ordered_json merges_json(const VirtualTopology& vt) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const FaceMerge& m : vt.merges)
    out.push_back({{"face", m.face}, {"merged_into", m.into ? nlohmann::ordered_json(m.into) : nullptr}, {"reason", m.reason}, {"width", m.width},
                   {"dihedral_degrees", m.dihedral}, {"shared_edges", m.shared_edges}});
  return out;
}

std::vector<int> merged_into(const VirtualTopology& vt, int face) {
  std::vector<int> out;
  for (const FaceMerge& m : vt.merges)
    if (m.into == face) out.push_back(m.face);
  return out;
}

}  // namespace wefm_cli
