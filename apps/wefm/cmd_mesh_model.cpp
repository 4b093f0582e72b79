// wefm mesh-model MODEL.step --size h -o model.msh|.obj|.vtk|.vtu|.ply [-j N] [flatten options]
//
// The paper's whole-model pipeline (§1.2): every model edge is discretised once in 3D at size h
// (cad_edge_nodes), each face is flattened, gets those nodes on its edges (wefm_face_set_edge_nodes),
// is meshed in its domain and mapped back (wefm_face_mesh_domain); the face meshes are welded along
// their shared edge nodes into one conforming surface mesh (model_mesh).
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <thread>

#include "owned.hpp"
#include "command.hpp"
#include "coincident_faces.hpp"
#include "conformal_first.hpp"
#include "exit_codes.hpp"

#ifdef WEFM_CLI_HAVE_OCCT
#include "cad_plugin_loader.hpp"
#include "cad_edge_nodes.hpp"
#include "cad_model.hpp"
#include "cad_wefm.hpp"
#include "face_threads.hpp"
#include "flatten_settings.hpp"
#include "mesh_formats.hpp"
#include "mapped_faces.hpp"
#include "mapped_mesh.hpp"
#include "mapped_tubes.hpp"
#include "model_mesh.hpp"
#include "output_file.hpp"
#include "size_query.hpp"
#include "output_paths.hpp"
#include "progress.hpp"
#include "virtual_faces.hpp"
#endif

namespace wefm_cli {

namespace {

#ifdef WEFM_CLI_HAVE_OCCT

using Json = nlohmann::ordered_json;

// Triangles a whole-model mesh may need before it is refused unless the caller says otherwise, and
// about what one costs in the tool's peak memory (face meshes, the welded mesh, the output), from a
// measured whole-model mesh, rounded up (docs/PERFORMANCE.md, "Measurements behind design choices").
constexpr long long kDefaultMaxElements = 50'000'000;
constexpr double kBytesPerTriangle = 400;

std::vector<OptionSpec> mesh_model_specs() {
  const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
  const wefm_cad::TessellationSettings d;
  wefm_mesh_options m;
  wefm_mesh_options_init(&m, sizeof m);
  char defl[32], ang[32], smooth[16];
  std::snprintf(defl, sizeof defl, "%g", d.relative_deflection);
  std::snprintf(ang, sizeof ang, "%g", d.angular_deflection);
  std::snprintf(smooth, sizeof smooth, "%d", m.smoothing_iterations);
  std::vector<OptionSpec> specs = {
      {"output", 'o', "FILE.msh", "the whole-model mesh, format by extension: .msh (Gmsh MSH 4.1 ASCII), .obj, .vtk, .vtu, .ply (required)", "", false},
      {"size", 0, "H", "target element size in model units (required unless --size-ratio)", "", false},
      {"size-ratio", 0, "R", "target size as a fraction of the bounding-box diagonal (e.g. 0.025 = 1/40)", "", false},
      {"jobs", 'j', "N", "faces meshed at the same time, one thread and one handle each", std::to_string(hw), false},
      {"deflection", 0, "D", "BRepMesh linear deflection as a fraction of the bounding-box diagonal", defl, false},
      {"angular-deflection", 0, "RAD", "BRepMesh angular deflection in radians", ang, false},
      {"no-local-size", 0, "", "use H on every face, also on faces narrower than H", "", false},
      {"no-merge-faces", 0, "", "mesh every B-rep face on its own (default: a face narrower than H / 30 or with a "
                                "corner under 12 degrees is meshed together with its smoothest neighbour, its "
                                "triangles still written as its own)", "", false},
      {"transfinite", 0, "N", "mesh face N transfinite (four-sided faces; a face whose opposite sides get different node "
                              "counts is meshed free, with a note)", "", true},
      {"mapped", 0, "auto|named", "auto: every four-sided face (one loop, four corners of 30 to 150 degrees, opposite "
                                  "sides within 3x) is meshed transfinite, the node counts of opposite sides matched "
                                  "across the model by adding segments (at most doubling an edge's); a face that cannot "
                                  "be matched, or whose grid would have a scaled Jacobian under 0.3, is meshed free. "
                                  "named: only the --transfinite faces", "auto with quads, named with tri", false},
      {"mapped-grid-limit", 0, "R", "a face found four-sided keeps its grid only if it has at most R times the elements of "
                                    "the face's free mesh (a grid carries an edge's fine segments all across the face; "
                                    "the free mesh is then made too); 0: any grid", "0", false},
      {"no-mapped-tubes", 0, "", "mesh thin tubes free (default: a tube narrower than H, a seam and two ends with as "
                                 "many segments, is meshed as a mapped strip, elements twice as long as wide along its axis)", "", false},
      {"smoothing", 0, "N", "smoothing passes of free meshes (from the fourth, only nodes of elements under lambda 0.6), then up to 3 optimisation passes (0: neither)", smooth, false},
      {"elements", 0, "tri|quad-dominant|quad", "free faces: triangles, or quads where pairs of triangles make good ones "
                                               "(scaled Jacobian >= 0.3; mapped faces then keep their quads too), or all quads: "
                                               "every element of those split into quads at its edges' middles and centre, "
                                               "mapped faces' grids halved, sides about H / 2 (as Gmsh's subdivision)", "tri", false},
      {"max-elements", 0, "N", "refuse (exit 5) before meshing when the model would need more triangles than N, "
                               "and cap each face's refinement at N; 0 = no limit", std::to_string(kDefaultMaxElements), false},
      {"report", 0, "FILE.json", "quality report per face and overall", "", false},
      {"quiet", 'q', "", "no per-face progress lines", "", false},
  };
  for (auto& s : solver_option_specs()) {
    if (s.name == "s")
      s.default_text = "0 (conformal), then 1 on a face whose conformal domain has a flipped triangle, crosses itself or "
                       "is refused by the mesher";
    if (s.name != "edge-mode-of") specs.push_back(s);
  }
  return specs;
}

void print_help() {
  std::printf(
      "Usage: wefm mesh-model MODEL.step|.iges|.brep (--size H | --size-ratio R) -o FILE.msh [options]\n\n"
      "Meshes a whole CAD model the paper's way: every model edge is discretised once in 3D at size H, so\n"
      "the faces sharing it get the same nodes; each face is flattened, meshed in its domain (free, or\n"
      "transfinite: four-sided faces with quad elements, faces named with --transfinite, thin tubes) and\n"
      "mapped back; the face meshes are welded into one conforming surface mesh. Writes Gmsh MSH 4.1\n"
      "ASCII (a physical group \"face_N\" per face), OBJ (a group per face), VTK, VTU or PLY (face_id per\n"
      "triangle); prints Lo's lambda per face and overall and the conformity count.\n\n%s\nOptions:\n%s\n%s",
      mesh_formats_help(), format_options(mesh_model_specs()).c_str(), exit_codes_help());
}

struct FaceMeshRun {
  const wefm_cad::CadFace* face = nullptr;
  int exit_code = kExitOk;
  std::string status = "ok", reason;
  std::vector<double> xyz;
  std::vector<int32_t> tris;
  std::vector<int32_t> quad_of;  // per triangle: the face mesh's quad it is half of, or -1 (empty: no quads)
  wefm_mesh_report report{};
  double time_solve = 0, time_mesh = 0;
  double score = NAN;
  double s = NAN;  // the roll-out exponent of the flattening meshed (NaN: none)
  std::string conformal_refused;  // why the conformal flattening was not meshed, where it was tried
  int64_t flips = 0;
  int64_t global_flips = -1;     // the global solve's flips where roll-out replaced it (retry_by_rollout), else -1
  int64_t domain_crossings = 0;  // crossing pairs of the flattened domain's own boundary, at the tessellation's resolution
  wefm_status mesh_status = WEFM_OK;  // what the domain meshing returned, if it ran
  int edge_refinements = 0;           // times its size was halved (refine_for_failed_faces, repair_defect_faces)
  bool split_chords = false;          // meshed with every chord off the surface split (repair_defect_faces)
  int copy_of = 0;                    // the face whose mesh it has (a face lying on it), or 0
  std::string type = "free";          // how it was meshed: free or transfinite
  std::string mapped_refused;         // why a face meant to be mapped was meshed free
  LambdaStats quality;                // of its final mesh, for the table and the report
};

// The run of a face to be meshed again: nothing but its face, how often its edges were refined and
// whether its chords are split.
void reset_run(FaceMeshRun& r, int edge_refinements) {
  const wefm_cad::CadFace* face = r.face;
  const bool split_chords = r.split_chords;
  r = FaceMeshRun{};
  r.face = face;
  r.edge_refinements = edge_refinements;
  r.split_chords = split_chords;
}

Json defect_edges_json(const ConformityCounts& conf) {
  Json out = Json::array();
  for (const auto& d : conf.defect_edges)
    out.push_back({{"midpoint", {d.midpoint[0], d.midpoint[1], d.midpoint[2]}}, {"uses", d.uses}, {"expected", d.expected}});
  return out;
}

// One flattening of the face at `options` and its domain mesh, into r. `last`: no other s follows,
// so a conformal domain that is unusable is meshed anyway (and fails or not as the mesher says).
// `mapped` (or null): tried first, free where the library refuses it or its grid is below its floor.
void flatten_and_mesh(FaceMeshRun& r, const wefm_options& options, bool last, const wefm_mesh_options& mesh_options,
                      const MappedRequest* mapped, const std::map<long long, wefm_cad::EdgeNodes>& edge_nodes,
                      CancelWatcher& watcher) {
  auto fail = [&](int code, const std::string& why) {
    r.exit_code = code;
    r.status = "failed";
    r.reason = why;
  };
  if (!r.face->error.empty()) return fail(kExitInvalid, "import: " + r.face->error);
  wefm_face* raw = nullptr;
  if (wefm_face_create(&raw) != WEFM_OK) return fail(kExitSolver, wefm_last_error());
  std::unique_ptr<wefm_face, FaceDeleter> face(raw);
  std::string error;
  if (wefm_cad::set_face_from_cad(raw, *r.face, error) != WEFM_OK) return fail(kExitInvalid, error);
  if (wefm_face_set_options(raw, &options) != WEFM_OK) return fail(kExitUsage, wefm_face_last_error(raw));
  if (wefm_face_build(raw) != WEFM_OK) return fail(kExitInvalid, std::string("topology: ") + wefm_face_last_error(raw));
  const auto t0 = Clock::now();
  wefm_status st;
  {
    WatchedFace watched(&watcher, raw);
    st = wefm_face_solve(raw);
  }
  r.time_solve += since(t0);
  r.s = options.s;
  int32_t has = 0;
  wefm_face_has_result(raw, &has);
  if (st != WEFM_OK && !(st == WEFM_ERROR_NOT_CONVERGED && has))
    return fail(st == WEFM_ERROR_CANCELLED ? stop_exit_code() : kExitSolver,
                std::string("flatten: ") + wefm_face_last_error(raw) + " [" + wefm_status_string(st) + "]");
  wefm_report rep;
  wefm_report_init(&rep, sizeof rep);
  rep.score = NAN;  // unknown unless the library reports it
  if (wefm_face_get_report(raw, &rep) == WEFM_OK) {
    r.score = rep.score;
    r.flips = rep.flipped_triangles;
    r.domain_crossings = rep.boundary_intersections;
  }
  if (!last)
    if (const char* why = conformal_unusable(rep)) return fail(kExitSolver, why);
  if (st == WEFM_ERROR_NOT_CONVERGED) {
    r.status = "not_converged";
    r.reason = std::string("flatten: ") + wefm_face_last_error(raw);
  }
  for (size_t k = 0; k < r.face->edges.size(); ++k) {
    const auto it = edge_nodes.find(r.face->edges[k].id);
    if (it == edge_nodes.end()) continue;  // degenerate: a point
    const auto& xyz = it->second.xyz;
    if (wefm_face_set_edge_nodes(raw, static_cast<int32_t>(k), static_cast<int64_t>(xyz.size() / 3), xyz.data()) != WEFM_OK)
      return fail(kExitInvalid, "edge id " + std::to_string(r.face->edges[k].id) + " nodes: " + wefm_face_last_error(raw));
  }
  const auto t1 = Clock::now();
  wefm_domain_mesh* dm_raw = nullptr;
  {
    WatchedFace watched(&watcher, raw);
    r.type = "free";
    if (mapped) {
      const MappedOutcome m = mesh_mapped(raw, *mapped, mesh_options, &dm_raw);
      st = m.status;
      if (m.transfinite) r.type = "transfinite";
      r.mapped_refused = m.refused;
    } else {
      st = wefm_face_mesh_domain(raw, &mesh_options, &dm_raw);
    }
  }
  std::unique_ptr<wefm_domain_mesh, DomainMeshDeleter> dm(dm_raw);
  r.time_mesh += since(t1);
  r.mesh_status = st;
  if (st != WEFM_OK || !dm_raw) {
    std::string why = std::string("mesh: ") + wefm_face_last_error(raw) + " [" + wefm_status_string(st) + "]";
    if (st == WEFM_ERROR_INVALID_STATE && r.domain_crossings > 0)
      why += "; the flattened face's own boundary crosses itself (" + std::to_string(r.domain_crossings) +
             " crossing pairs at the tessellation's resolution: a folded tessellation?), so its edges were not refined";
    return fail(st == WEFM_ERROR_CANCELLED ? stop_exit_code() : kExitSolver, why);
  }
  wefm_mesh_report_init(&r.report, sizeof r.report);
  wefm_domain_mesh_get_report(dm_raw, &r.report);
  std::vector<int32_t> elements;
  if (fetch(r.xyz, [&](double* b, int64_t c, int64_t* n) { return wefm_domain_mesh_get_xyz(dm_raw, b, c, n); }) != WEFM_OK ||
      fetch(elements, [&](int32_t* b, int64_t c, int64_t* n) { return wefm_domain_mesh_get_elements(dm_raw, b, c, n); }) != WEFM_OK)
    return fail(kExitSolver, std::string("mesh: reading the result: ") + wefm_face_last_error(raw));
  if (r.report.nodes_per_element == 4) {
    // Quads (transfinite, quad-dominant, all quads): split along the shorter diagonal, so the model
    // mesh is welded and checked as triangles; with quads asked for, the halves are numbered (quad_of),
    // split again where welding asks for it (ModelMesh::add_face), and the file gets the quads back.
    // A quad-dominant mesh's triangle ends in -1.
    const bool keep = mesh_options.elements != WEFM_ELEMENTS_TRIANGLES;
    r.tris.clear(), r.quad_of.clear();
    for (size_t q = 0; q + 3 < elements.size(); q += 4) {
      const int32_t a = elements[q], b = elements[q + 1], c = elements[q + 2], d = elements[q + 3];
      if (d < 0) {
        r.tris.insert(r.tris.end(), {a, b, c});
        if (keep) r.quad_of.push_back(-1);
        continue;
      }
      if (keep) r.quad_of.insert(r.quad_of.end(), 2, static_cast<int32_t>(q / 4));
      auto dist2 = [&](int32_t i, int32_t j) {
        double s = 0;
        for (int k = 0; k < 3; ++k) {
          const double x = r.xyz[3 * static_cast<size_t>(i) + static_cast<size_t>(k)] - r.xyz[3 * static_cast<size_t>(j) + static_cast<size_t>(k)];
          s += x * x;
        }
        return s;
      };
      if (dist2(a, c) <= dist2(b, d)) r.tris.insert(r.tris.end(), {a, b, c, a, c, d});
      else r.tris.insert(r.tris.end(), {a, b, d, b, c, d});
    }
  } else {
    r.tris = std::move(elements);
    r.quad_of.clear();
  }
}

// A face whose last flattening still has flipped triangles is flattened again by roll-out (paper
// §4.1), and that domain is kept where it has fewer flips and its mesh succeeded. A coarse
// tessellation of a strongly curved face can leave the global solve flipped at every s: gmsh_ellipses'
// B-spline face 45 at a deflection of 0.003 of the diagonal had 19 flips at s = 1 and a mesh of 5570
// triangles with min Lo lambda 0.003; by roll-out 0 flips, 56 triangles, min 0.71. Roll-out's sweeps
// grow with the face and, on a face whose flips come from a folded tessellation, end at the sweep
// limit with no fewer flips (pyocc_surf114's face 4, 8552 facets, took many times its global solve):
// only faces of at most kRolloutFacets facets are retried, with at most kRolloutSweeps sweeps, where
// ellipses' face 45 already has no flip.
constexpr size_t kRolloutFacets = 2000;
constexpr int kRolloutSweeps = 1000;

void retry_by_rollout(FaceMeshRun& r, const wefm_options& options, const wefm_mesh_options& mesh_options, const MappedRequest* mapped,
                      const std::map<long long, wefm_cad::EdgeNodes>& edge_nodes, CancelWatcher& watcher) {
  if (r.face->triangles.size() / 3 > kRolloutFacets || r.exit_code == stop_exit_code()) return;
  FaceMeshRun retry;
  retry.face = r.face;
  retry.edge_refinements = r.edge_refinements;
  retry.split_chords = r.split_chords;
  wefm_options rollout = options;
  rollout.method = WEFM_METHOD_ROLLOUT;
  rollout.max_rollout_sweeps = kRolloutSweeps;
  flatten_and_mesh(retry, rollout, true, mesh_options, mapped, edge_nodes, watcher);
  const bool better = retry.status != "failed" && (retry.flips < r.flips || r.status == "failed");
  retry.time_solve += r.time_solve, retry.time_mesh += r.time_mesh;
  if (!better) {
    r.time_solve = retry.time_solve, r.time_mesh = retry.time_mesh;
    return;
  }
  retry.conformal_refused = r.conformal_refused;
  retry.global_flips = r.flips;
  r = std::move(retry);
}

// `mapped` (or null): transfinite options tried first; where the library refuses them (not four
// sides with matching node counts), or their grid is below its floor, the face is meshed with
// `mesh_options` on the same domain.
// `conformal_first`: kConformalS is tried before the settings' s (conformal_first.hpp).
void mesh_one_face(FaceMeshRun& r, const FlattenSettings& settings, bool conformal_first, const wefm_mesh_options& mesh_options,
                   const MappedRequest* mapped, const std::map<long long, wefm_cad::EdgeNodes>& edge_nodes, CancelWatcher& watcher) {
  if (conformal_first && settings.options.s != kConformalS) {
    wefm_options conformal = settings.options;
    conformal.s = kConformalS;
    flatten_and_mesh(r, conformal, false, mesh_options, mapped, edge_nodes, watcher);
    if (r.status != "failed" || r.exit_code == stop_exit_code() || r.exit_code == kExitInvalid || r.exit_code == kExitUsage) return;
    const double time_solve = r.time_solve, time_mesh = r.time_mesh;
    const std::string why = r.reason;
    reset_run(r, r.edge_refinements);
    r.time_solve = time_solve, r.time_mesh = time_mesh, r.conformal_refused = why;
  }
  flatten_and_mesh(r, settings.options, true, mesh_options, mapped, edge_nodes, watcher);
  if (r.flips > 0 && settings.options.method == WEFM_METHOD_GLOBAL) retry_by_rollout(r, settings.options, mesh_options, mapped, edge_nodes, watcher);
}

// About how many triangles the faces need at their sizes: each face's area over an equilateral
// triangle's of side its size.
double estimated_triangles(const wefm_cad::CadModel& model, const std::vector<double>& face_sizes) {
  double total = 0;
  for (size_t k = 0; k < model.faces.size(); ++k) {
    total += wefm_cad::face_area(model.faces[k]) / (0.433 * face_sizes[k] * face_sizes[k]);
  }
  return total;
}

// The domain mesher breaks a face's boundary at a sharp corner of its flattened domain; a corner
// inside a model edge (a kink of the edge's facet chain) gets a node there that the edge's given
// nodes do not have. The other faces on the edge then lack it (a T-junction: a crack in the model's
// mesh), and even on a seam, used by its one face, the given segment over it is not in the mesh.
// Such a node is a node of the edge: it joins the edge's nodes, and every face on the edge whose
// mesh does not have it is meshed again with it. At most this many rounds.
constexpr int kEdgeNodeAdoptions = 3;

struct EdgeNode {
  double s;  // arc length along the edge's chain
  std::array<double, 3> p;
};

double distance3(const double* a, const double* b) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

// Distance of p from the segment a b; t: where the closest point is (0 at a, 1 at b).
double off_segment(const double* a, const double* b, const double* p, double& t) {
  const double len = distance3(a, b);
  t = 0;
  if (len > 0) {
    for (int c = 0; c < 3; ++c) t += (p[c] - a[c]) * (b[c] - a[c]);
    t = std::clamp(t / (len * len), 0.0, 1.0);
  }
  const double x[3] = {a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2])};
  return distance3(p, x);
}

PointGrid boundary_grid(const FaceMeshRun& r, double tol) {
  PointGrid grid(tol);
  const std::vector<char> boundary = ModelMesh::boundary_nodes(r.xyz.size() / 3, r.tris);
  for (size_t v = 0; v < boundary.size(); ++v)
    if (boundary[v]) grid.add(&r.xyz[3 * v], static_cast<int32_t>(v));
  return grid;
}

// The nodes an edge's segments end in, in the faces' meshes: its given nodes, and with all quads
// (`halved`) also each segment's middle, which the library puts at the middle of the 3D chord in
// every face using the edge (WEFM_ELEMENTS_QUADS), and mapped faces too.
std::vector<double> segment_nodes(const std::vector<double>& given, bool halved) {
  if (!halved || given.size() < 6) return given;
  std::vector<double> out;
  out.reserve(2 * given.size());
  for (size_t k = 0; k + 2 < given.size(); k += 3) {
    if (k > 0)
      for (size_t c = 0; c < 3; ++c) out.push_back(0.5 * (given[k - 3 + c] + given[k + c]));
    out.insert(out.end(), &given[k], &given[k] + 3);
  }
  return out;
}

// Interior chain vertices of the face's edges where its mesh has a boundary node the edge's nodes
// (segment_nodes) do not have, by edge id.
void nodes_put_on_edges(const FaceMeshRun& r, const std::map<long long, wefm_cad::EdgeNodes>& edge_nodes, double tol, bool halved,
                        std::map<long long, std::vector<EdgeNode>>& out) {
  if (r.tris.empty()) return;
  const PointGrid grid = boundary_grid(r, tol);
  const wefm_cad::CadFace& f = *r.face;
  for (const wefm_cad::CadEdge& e : f.edges) {
    const auto it = edge_nodes.find(e.id);
    if (it == edge_nodes.end()) continue;
    const std::vector<double> given = segment_nodes(it->second.xyz, halved);
    double s = 0;
    for (size_t k = 1; k + 1 < e.vertices.size(); ++k) {
      const double* p = &f.xyz[3 * static_cast<size_t>(e.vertices[k])];
      s += distance3(&f.xyz[3 * static_cast<size_t>(e.vertices[k - 1])], p);
      if (grid.find(p, r.xyz) < 0) continue;
      bool known = false;
      for (size_t g = 0; g + 2 < given.size() && !known; g += 3) known = distance3(p, &given[g]) <= tol;
      if (!known) out[e.id].push_back({s, {p[0], p[1], p[2]}});
    }
  }
}

// The edge's nodes with `added` among them, in order of arc length along the face's chain of the edge.
std::vector<double> with_nodes(const wefm_cad::CadFace& f, const wefm_cad::CadEdge& e, const std::vector<double>& nodes,
                               std::vector<EdgeNode> added, double tol) {
  std::vector<EdgeNode> all;
  const size_t n = nodes.size() / 3, m = e.vertices.size();
  auto at = [&](size_t k) { return &f.xyz[3 * static_cast<size_t>(e.vertices[k])]; };
  // The nodes lie on the chain in order: each is found on the first segment, from the previous
  // one's on, that passes within the tolerance (the ends of a closed edge are the chain's ends).
  size_t seg = 0;
  double s0 = 0;  // arc length at the start of segment seg
  for (size_t j = 0; j < n; ++j) {
    const double* p = &nodes[3 * j];
    double s = j + 1 == n ? -1 : s0;
    for (size_t q = seg; q + 1 < m && j + 1 < n; ++q) {
      const double len = distance3(at(q), at(q + 1));
      double t = 0;
      if (off_segment(at(q), at(q + 1), p, t) <= tol) {
        s = s0 + t * len;
        break;
      }
      s0 += len, seg = q + 1;
    }
    all.push_back({s, {p[0], p[1], p[2]}});
  }
  double total = 0;
  for (size_t k = 0; k + 1 < m; ++k) total += distance3(at(k), at(k + 1));
  if (!all.empty()) all.back().s = total;
  for (const EdgeNode& a : added)
    if (std::none_of(all.begin(), all.end(), [&](const EdgeNode& b) { return distance3(a.p.data(), b.p.data()) <= tol; }))
      all.push_back(a);
  std::stable_sort(all.begin(), all.end(), [](const EdgeNode& a, const EdgeNode& b) { return a.s < b.s; });
  std::vector<double> out;
  for (const EdgeNode& a : all) out.insert(out.end(), a.p.begin(), a.p.end());
  return out;
}

// Arc length along the face's chain of edge e at which it passes within `tol` of p, or -1.
double arc_length_at(const wefm_cad::CadFace& f, const wefm_cad::CadEdge& e, const double* p, double tol) {
  double s0 = 0;
  for (size_t q = 0; q + 1 < e.vertices.size(); ++q) {
    const double* a = &f.xyz[3 * static_cast<size_t>(e.vertices[q])];
    const double* b = &f.xyz[3 * static_cast<size_t>(e.vertices[q + 1])];
    const double len = distance3(a, b);
    double t = 0;
    if (off_segment(a, b, p, t) <= tol) return s0 + t * len;
    s0 += len;
  }
  return -1;
}

double chain_length3(const wefm_cad::CadFace& f, const wefm_cad::CadEdge& e) {
  double len = 0;
  for (size_t q = 0; q + 1 < e.vertices.size(); ++q)
    len += distance3(&f.xyz[3 * static_cast<size_t>(e.vertices[q])], &f.xyz[3 * static_cast<size_t>(e.vertices[q + 1])]);
  return len;
}

bool has_edge(const wefm_cad::CadFace& f, long long id) {
  return std::any_of(f.edges.begin(), f.edges.end(), [&](const wefm_cad::CadEdge& e) { return e.id == id; });
}

// Faces lying on each other whose edges are not the same (a neighbour of one volume splits an edge
// the other does not have) carry different nodes and cannot be meshed alike. The later face's edges
// take the earlier face's nodes that lie on them, besides their own ends (`replaced`), and the
// earlier face's edges get the later one's vertices that lie inside them (`added`): the two then
// have the same nodes, and only a vertex of one can come close to a node of the other (a union of
// both node sets would put pairs of close nodes all along: slivers).
void coincident_nodes(const wefm_cad::CadModel& model, const std::vector<size_t>& source,
                      const std::map<long long, wefm_cad::EdgeNodes>& edge_nodes, double tol,
                      std::map<long long, std::vector<EdgeNode>>& added, std::map<long long, std::vector<double>>& replaced) {
  for (size_t j = 0; j < source.size(); ++j) {
    if (!source[j]) continue;
    const wefm_cad::CadFace& later = model.faces[j];
    const wefm_cad::CadFace& earlier = model.faces[source[j] - 1];
    for (const wefm_cad::CadEdge& d : later.edges) {
      const auto it = edge_nodes.find(d.id);
      if (it == edge_nodes.end() || has_edge(earlier, d.id)) continue;
      const std::vector<double>& own = it->second.xyz;
      const double total = chain_length3(later, d);
      std::vector<EdgeNode> list{{0.0, {own[0], own[1], own[2]}}, {total, {own[own.size() - 3], own[own.size() - 2], own.back()}}};
      for (const wefm_cad::CadEdge& e : earlier.edges) {
        const auto jt = edge_nodes.find(e.id);
        if (jt == edge_nodes.end()) continue;
        for (size_t k = 0; k + 2 < jt->second.xyz.size(); k += 3) {
          const double* p = &jt->second.xyz[k];
          const double s = arc_length_at(later, d, p, tol);
          if (s > 0 && s < total && distance3(p, list[0].p.data()) > tol && distance3(p, list[1].p.data()) > tol)
            list.push_back({s, {p[0], p[1], p[2]}});
        }
        // The later face's vertex inside this edge of the earlier one.
        for (const double* p : {own.data(), own.data() + own.size() - 3}) {
          bool known = false;
          for (size_t g = 0; g + 2 < jt->second.xyz.size() && !known; g += 3) known = distance3(p, &jt->second.xyz[g]) <= tol;
          const double s = known ? -1 : arc_length_at(earlier, e, p, tol);
          if (s > 0) added[e.id].push_back({s, {p[0], p[1], p[2]}});
        }
      }
      std::stable_sort(list.begin(), list.end(), [](const EdgeNode& x, const EdgeNode& y) { return x.s < y.s; });
      std::vector<double> xyz;
      for (size_t k = 0; k < list.size(); ++k)
        if (k == 0 || distance3(list[k].p.data(), &xyz[xyz.size() - 3]) > tol) xyz.insert(xyz.end(), list[k].p.begin(), list[k].p.end());
      if (xyz.size() >= 6 && xyz != own) replaced[d.id] = std::move(xyz);
    }
  }
}

// Adds the nodes the face meshes put on model edges, and those faces lying on each other need from
// each other, to those edges; returns the faces to mesh again
// (those on such an edge whose mesh lacks one of its nodes), reset for meshing.
std::vector<size_t> adopt_edge_nodes(const wefm_cad::CadModel& model, std::vector<FaceMeshRun>& runs,
                                     std::map<long long, wefm_cad::EdgeNodes>& edge_nodes, double tol,
                                     const std::vector<size_t>& source, bool halved) {
  std::map<long long, std::vector<EdgeNode>> added;
  std::map<long long, std::vector<double>> replaced;
  for (const FaceMeshRun& r : runs) nodes_put_on_edges(r, edge_nodes, tol, halved, added);
  coincident_nodes(model, source, edge_nodes, tol, added, replaced);
  if (added.empty() && replaced.empty()) return {};
  std::set<long long> changed;
  for (auto& [id, xyz] : replaced) edge_nodes[id].xyz = std::move(xyz), changed.insert(id);
  for (const wefm_cad::CadFace& f : model.faces)
    for (const wefm_cad::CadEdge& e : f.edges)
      if (added.count(e.id) && changed.insert(e.id).second)
        edge_nodes[e.id].xyz = with_nodes(f, e, edge_nodes[e.id].xyz, added[e.id], tol);
  std::vector<size_t> todo;
  for (size_t i = 0; i < runs.size(); ++i) {
    bool lacks = false;
    std::unique_ptr<PointGrid> grid;
    for (const wefm_cad::CadEdge& e : model.faces[i].edges) {
      if (!changed.count(e.id) || runs[i].tris.empty()) continue;
      if (!grid) grid = std::make_unique<PointGrid>(boundary_grid(runs[i], tol));
      const std::vector<double>& xyz = edge_nodes[e.id].xyz;
      for (size_t k = 0; k + 2 < xyz.size() && !lacks; k += 3) lacks = grid->find(&xyz[k], runs[i].xyz) < 0;
    }
    if (lacks) todo.push_back(i);
  }
  for (size_t i : todo) reset_run(runs[i], runs[i].edge_refinements);
  return todo;
}

// The later of two faces lying on each other (coincident_faces) gets the earlier one's mesh,
// turned over when they face opposite ways, instead of a mesh of its own flattening, which would
// differ. Gives face j the mesh of face i when every node on j's edges is a boundary node of i's mesh and
// every boundary node of i's mesh lies on j's edge chains; false (j to be meshed itself) otherwise.
bool copy_coincident(FaceMeshRun& j, const FaceMeshRun& i, const std::map<long long, wefm_cad::EdgeNodes>& edge_nodes, double tol,
                     bool halved) {
  if (i.tris.empty() || i.status == "failed") return false;
  const PointGrid grid = boundary_grid(i, tol);
  PointGrid chain(tol);
  std::vector<double> chain_xyz;
  const wefm_cad::CadFace& f = *j.face;
  for (const wefm_cad::CadEdge& e : f.edges) {
    for (int32_t v : e.vertices) {
      chain.add(&f.xyz[3 * static_cast<size_t>(v)], static_cast<int32_t>(chain_xyz.size() / 3));
      chain_xyz.insert(chain_xyz.end(), &f.xyz[3 * static_cast<size_t>(v)], &f.xyz[3 * static_cast<size_t>(v)] + 3);
    }
    const auto it = edge_nodes.find(e.id);
    if (it == edge_nodes.end()) continue;
    const std::vector<double> nodes = segment_nodes(it->second.xyz, halved);
    for (size_t k = 0; k + 2 < nodes.size(); k += 3) {
      if (grid.find(&nodes[k], i.xyz) < 0) return false;
      chain.add(&nodes[k], static_cast<int32_t>(chain_xyz.size() / 3));
      chain_xyz.insert(chain_xyz.end(), &nodes[k], &nodes[k] + 3);
    }
  }
  const std::vector<char> boundary = ModelMesh::boundary_nodes(i.xyz.size() / 3, i.tris);
  for (size_t v = 0; v < boundary.size(); ++v)
    if (boundary[v] && chain.find(&i.xyz[3 * v], chain_xyz) < 0) return false;
  const FaceShape a = shape_of(*i.face), b = shape_of(f);
  const bool flip = a.normal[0] * b.normal[0] + a.normal[1] * b.normal[1] + a.normal[2] * b.normal[2] < 0;
  j.xyz = i.xyz;
  j.tris = i.tris;
  j.quad_of = i.quad_of;
  if (flip)
    for (size_t t = 0; t + 2 < j.tris.size(); t += 3) std::swap(j.tris[t + 1], j.tris[t + 2]);
  j.report = i.report;
  j.status = "ok";
  j.reason.clear();
  j.exit_code = kExitOk;
  j.copy_of = i.face->index;
  return true;
}

// What the command line asks for, checked.
struct MeshModelRequest {
  FlattenSettings settings;
  std::string model_path, out_path, report_path;  // report_path empty: no report
  MeshFormat format = MeshFormat::msh;
  double size = 0;  // model units, or a fraction of the diagonal (size_is_ratio)
  bool size_is_ratio = false;
  long long jobs = 1, max_elements = kDefaultMaxElements, smoothing = -1;
  wefm_cad::TessellationSettings tess;
  std::set<long long> transfinite;  // face numbers
  bool quiet = false, local_size = true, merge_faces = true, mapped_tubes = true;
  bool mapped_auto = false;  // four-sided faces found and mapped (--mapped auto)
  double mapped_grid_limit = 0;  // --mapped-grid-limit: a grid with more than this many times the free mesh's elements is not kept (0: any)
  bool conformal_first = true;  // no --s: kConformalS first
  int elements = WEFM_ELEMENTS_TRIANGLES;
};

// Parses and checks the arguments. Returns -1 to go on, else the exit code (help printed, bad usage).
int parse_request(const std::vector<std::string>& argv, MeshModelRequest& q) {
  const auto specs = mesh_model_specs();
  ParsedArgs args;
  std::string error;
  auto usage = [](const std::string& message) {
    std::fprintf(stderr, "wefm mesh-model: %s\n", message.c_str());
    return kExitUsage;
  };
  if (!parse_args(argv, specs, args, error) || (!args.help && !apply_solver_options(args, q.settings, error)))
    return usage(error + " (see wefm mesh-model --help)");
  q.conformal_first = !args.has("s");
  if (args.help) {
    print_help();
    return kExitOk;
  }
  if (args.positionals.size() != 1 || !args.has("output") || args.has("size") == args.has("size-ratio"))
    return usage("expected one MODEL, -o FILE and one of --size or --size-ratio (see --help)");
  q.out_path = args.value("output");
  if (!mesh_format_of(q.out_path, q.format, error)) return usage("-o: " + error);
  q.size_is_ratio = args.has("size-ratio");
  const char* size_opt = q.size_is_ratio ? "size-ratio" : "size";
  if (!parse_double(args.value(size_opt), q.size) || !(q.size > 0)) return usage(std::string("--") + size_opt + ": expected a number > 0");
  q.jobs = std::max(1u, std::thread::hardware_concurrency());
  if (args.has("jobs") && (!parse_int(args.value("jobs"), q.jobs) || q.jobs < 1 || q.jobs > 1024))
    return usage("-j: expected a thread count >= 1");
  if (args.has("max-elements") && (!parse_int(args.value("max-elements"), q.max_elements) || q.max_elements < 0))
    return usage("--max-elements: expected a count >= 0");
  if (args.has("smoothing") && (!parse_int(args.value("smoothing"), q.smoothing) || q.smoothing < 0))
    return usage("--smoothing: expected a count >= 0");
  if (args.has("elements")) {
    const std::string& e = args.value("elements");
    if (e != "tri" && e != "quad-dominant" && e != "quad") return usage("--elements: expected tri, quad-dominant or quad, got '" + e + "'");
    q.elements = e == "tri" ? WEFM_ELEMENTS_TRIANGLES : e == "quad" ? WEFM_ELEMENTS_QUADS : WEFM_ELEMENTS_QUAD_DOMINANT;
  }
  for (auto [name, field] : {std::pair<const char*, double*>{"deflection", &q.tess.relative_deflection},
                             std::pair<const char*, double*>{"angular-deflection", &q.tess.angular_deflection}})
    if (args.has(name) && (!parse_double(args.value(name), *field) || !(*field > 0)))
      return usage(std::string("--") + name + ": expected a number > 0");
  if (args.has("transfinite"))
    for (const std::string& v : args.values.at("transfinite")) {
      long long k = 0;
      if (!parse_int(v, k) || k < 1) return usage("--transfinite: expected a face number >= 1, got '" + v + "'");
      q.transfinite.insert(k);
    }
  q.quiet = args.has("quiet");
  q.local_size = !args.has("no-local-size");
  q.merge_faces = !args.has("no-merge-faces");
  q.mapped_tubes = !args.has("no-mapped-tubes");
  q.mapped_auto = q.elements != WEFM_ELEMENTS_TRIANGLES;
  if (args.has("mapped")) {
    const std::string& m = args.value("mapped");
    if (m != "auto" && m != "named") return usage("--mapped: expected auto or named, got '" + m + "'");
    q.mapped_auto = m == "auto";
  }
  if (args.has("mapped-grid-limit") && (!parse_double(args.value("mapped-grid-limit"), q.mapped_grid_limit) || !(q.mapped_grid_limit >= 0)))
    return usage("--mapped-grid-limit: expected a number >= 0");
  q.model_path = args.positionals[0];
  std::vector<NamedPath> outputs = {{"-o", q.out_path}};
  if (args.has("report")) {
    q.report_path = args.value("report");
    outputs.push_back({"--report", q.report_path});
  }
  if (!check_output_paths({{"MODEL", q.model_path}}, outputs, error)) return usage(error);
  return -1;
}

// How the model is to be meshed: sizes per face, faces merged, every model edge's nodes, the faces
// mapped. Decided before any face is meshed.
struct ModelPlan {
  std::vector<double> face_sizes;
  double gradation = 0;
  VirtualTopology virtual_faces;
  std::map<long long, wefm_cad::EdgeNodes> edge_nodes;
  std::set<size_t> tubes;   // thin tubes meshed as mapped strips (map_thin_tubes)
  MappedFaces mapping;      // named and four-sided faces meshed mapped (map_four_sided_faces)
  std::vector<size_t> source;  // per face, the earlier face it lies on + 1, or 0 (coincident_faces)
  std::vector<std::vector<FaceCorner>> corners;  // per face, its corners under kFloorCornerDegrees, after merging
  std::vector<wefm_cad::Cusp> cusps;              // where those of faces without an import error are, and their angles
  double time = 0;
};

// Every model edge discretised at the faces' sizes, then the thin tubes' and the mapped faces' edges
// given the counts their mapping needs.
void discretise_and_map(const MeshModelRequest& q, const wefm_cad::CadModel& model, double size, ModelPlan& plan) {
  plan.edge_nodes = wefm_cad::discretise_model_edges(model, size, plan.face_sizes, plan.gradation, plan.cusps);
  plan.tubes.clear();
  if (q.mapped_tubes && q.local_size) plan.tubes = map_thin_tubes(model, size, plan.face_sizes, plan.edge_nodes);
  std::vector<size_t> named;
  std::set<long long> unsettled;  // coincident_nodes changes them
  for (size_t i = 0; i < model.faces.size(); ++i) {
    if (q.transfinite.count(model.faces[i].index) && !plan.tubes.count(i)) named.push_back(i);
    if (plan.source[i])
      for (const wefm_cad::CadFace* f : {&model.faces[i], &model.faces[plan.source[i] - 1]})
        for (const wefm_cad::CadEdge& e : f->edges) unsettled.insert(e.id);
  }
  plan.mapping = map_four_sided_faces(model, named, q.mapped_auto, plan.tubes, unsettled, plan.edge_nodes);
}

// A face whose domain boundary, discretised at its edges' nodes, crosses itself (chords of a coarse
// edge cutting across a narrow part of the domain) is meshed again with finer nodes on its edges:
// its size halves, every edge whose nodes change is discretised again, and every face using such
// an edge is meshed again with the new nodes, so the model stays conforming. At most this many rounds
// (a face's size down to 1/256): at a size of a third of the diagonal nodeocc_kuka's slotted plates
// (faces 416 and 521) still crossed themselves after 3 and failed; rounds run only for such faces.
constexpr int kEdgeRefinements = 8;

// Only a crossing of the discretised boundary that the domain itself does not have: where the
// flattened tessellation's own boundary already crosses itself (a folded tessellation: pyocc_surf114's
// B-spline faces at a deflection of 0.0003), finer edge nodes cannot mend it. Refining there halved
// the face's size eight times, and with it every neighbour's edges, before the face failed anyway.
bool boundary_failure(const FaceMeshRun& r) {
  return r.status == "failed" && r.mesh_status == WEFM_ERROR_INVALID_STATE && r.domain_crossings == 0;
}

// Halves the size of `faces`, discretises the edges again and returns the faces to mesh again, reset:
// those, and every face using an edge whose nodes changed.
std::vector<size_t> refine_faces(const MeshModelRequest& q, const wefm_cad::CadModel& model, std::vector<FaceMeshRun>& runs, double size,
                                 ModelPlan& plan, std::set<size_t> faces) {
  if (faces.empty()) return {};
  for (size_t i : faces) plan.face_sizes[i] *= 0.5;
  const auto before = std::move(plan.edge_nodes);
  discretise_and_map(q, model, size, plan);
  std::set<long long> changed;
  for (const auto& [id, nodes] : plan.edge_nodes) {
    const auto it = before.find(id);
    if (it == before.end() || it->second.xyz != nodes.xyz) changed.insert(id);
  }
  for (size_t i = 0; i < runs.size(); ++i)
    for (const wefm_cad::CadEdge& e : model.faces[i].edges)
      if (changed.count(e.id)) faces.insert(i);
  std::vector<size_t> todo(faces.begin(), faces.end());
  for (size_t i : todo) reset_run(runs[i], runs[i].edge_refinements + 1);
  return todo;
}

std::vector<size_t> refine_for_failed_faces(const MeshModelRequest& q, const wefm_cad::CadModel& model, std::vector<FaceMeshRun>& runs,
                                            double size, ModelPlan& plan) {
  std::set<size_t> faces;
  for (size_t i = 0; i < runs.size(); ++i)
    if (boundary_failure(runs[i])) faces.insert(i);
  return refine_faces(q, model, runs, size, plan, std::move(faces));
}

// The faces the check finds at fault (their triangles on an edge used more or fewer times than the
// B-rep says, or of zero area) are meshed again, a face lying on another with that one:
// - first with every chord off the surface split (wefm_mesh_options.split_chords). Where two faces
//   share two boundary nodes across a part narrower than the size (a coarse half tube and its
//   symmetry plane, the two halves of a thin tube), each mesh may join them by the same straight
//   chord, an edge of four triangles once welded (gmsh_wing_fuselage, gmsh_918_pump_carter_sup and
//   nodeocc_battleship at 0.3 of the diagonal);
// - then at half their size, with their edges and the faces on those edges: at a size well above a
//   face's radius of curvature its mesh can lie on itself (occt_MODERN_Sink_1's B-spline face 55, a
//   tube of radius about 1.3 meshed at 1.95 = h / 8, at 0.1 of the diagonal).
// At most this many rounds, and none where a face failed (the edges around it are open whatever its
// neighbours do); what is left is reported as before.
constexpr int kRepairRounds = 3;

std::vector<size_t> repair_defect_faces(const MeshModelRequest& q, const wefm_cad::CadModel& model, std::vector<FaceMeshRun>& runs,
                                        double size, ModelPlan& plan, const std::vector<int>& defect_faces) {
  std::map<int, size_t> by_tag;
  for (size_t i = 0; i < runs.size(); ++i) by_tag[runs[i].face->index] = i;
  std::set<size_t> split, refine;
  for (int tag : defect_faces)
    if (const auto it = by_tag.find(tag); it != by_tag.end()) {
      const size_t i = plan.source[it->second] ? plan.source[it->second] - 1 : it->second;
      if (!runs[i].split_chords) split.insert(i);
      else if (runs[i].edge_refinements < kEdgeRefinements) refine.insert(i);
    }
  std::set<size_t> todo;
  for (size_t i : split) {
    reset_run(runs[i], runs[i].edge_refinements);
    runs[i].split_chords = true;
    todo.insert(i);
  }
  for (size_t i : refine_faces(q, model, runs, size, plan, std::move(refine))) todo.insert(i);
  return {todo.begin(), todo.end()};
}

// Returns -1 to go on, kExitUsage for a --transfinite face the model does not have, or kExitSolver
// when the model would need more than the limits allow. Merging faces (virtual_faces) changes `model`.
int plan_model(const MeshModelRequest& q, wefm_cad::CadModel& model, double size, ModelPlan& plan) {
  const auto t0 = Clock::now();
  // A face number past the model's is a typo or the wrong model: meshing it all free would hide it.
  if (!q.transfinite.empty() && *q.transfinite.rbegin() > static_cast<long long>(model.faces.size())) {
    std::fprintf(stderr, "wefm mesh-model: --transfinite %lld: %s has %zu faces\n", *q.transfinite.rbegin(), q.model_path.c_str(),
                 model.faces.size());
    return kExitUsage;
  }
  plan.face_sizes.assign(model.faces.size(), size);
  // Edges grade towards short neighbours at the rate (0.3 per unit length) the library grades a
  // face's inside from its short boundary segments, so the two meet without a jump.
  if (q.local_size) {
    plan.face_sizes = wefm_cad::local_face_sizes(model, size);
    plan.gradation = 0.3;
  }
  if (q.merge_faces) plan.virtual_faces = merge_narrow_faces(model, size, plan.face_sizes);
  // Before any edge is discretised: a size far below the model's (a typo, a unit mix-up) would
  // otherwise grow until memory runs out.
  // All quads: about two quads per triangle at H (a triangle makes three, two paired ones four), each
  // held as two triangles until written.
  const double estimate = estimated_triangles(model, plan.face_sizes) * (q.elements == WEFM_ELEMENTS_QUADS ? 2 : 1);
  const double estimate_mb = estimate * kBytesPerTriangle * (q.elements == WEFM_ELEMENTS_QUADS ? 2 : 1) / 1e6;
  const double memory_limit = q.settings.options.memory_limit_mb;
  if ((q.max_elements > 0 && estimate > static_cast<double>(q.max_elements)) || (memory_limit > 0 && estimate_mb > memory_limit)) {
    std::fprintf(stderr,
                 "wefm: %s at size %g would need about %.3g elements (about %.0f MB), above --max-elements %lld or "
                 "--memory-limit %g MB: refused before meshing (a larger --size, or raise the limits)\n",
                 q.model_path.c_str(), size, estimate, estimate_mb, q.max_elements, memory_limit);
    return kExitSolver;
  }
  plan.source = coincident_faces(model);
  // Once, for the edges (every refinement round discretises them again: refine_for_failed_faces) and
  // the report.
  for (const wefm_cad::CadFace& f : model.faces) {
    plan.corners.push_back(sharp_corners(f, kFloorCornerDegrees));
    if (f.error.empty())
      for (const FaceCorner& c : plan.corners.back())
        plan.cusps.push_back({{f.xyz[3 * static_cast<size_t>(c.vertex)], f.xyz[3 * static_cast<size_t>(c.vertex) + 1], f.xyz[3 * static_cast<size_t>(c.vertex) + 2]},
                              c.degrees, c.edges, edges_beyond(f, c)});
  }
  discretise_and_map(q, model, size, plan);
  plan.time = since(t0);
  return -1;
}

// Meshes the faces `todo` on `threads` threads (all at first, those a repair round reset later), then
// again those whose edges had to be refined or whose edge nodes a neighbour adopted. A face lying on
// an earlier one gets that one's mesh where it can (copy_coincident), also when only the earlier one
// was meshed again.
void mesh_model_faces(const MeshModelRequest& q, const wefm_cad::CadModel& model, double size, ModelPlan& plan,
                      std::vector<FaceMeshRun>& runs, size_t n_threads, double weld_tolerance, std::vector<size_t> todo) {
  wefm_mesh_options free_options, tf_options;
  wefm_mesh_options_init(&free_options, sizeof free_options);
  free_options.size = size;
  free_options.max_elements = q.max_elements;
  if (q.smoothing >= 0) free_options.smoothing_iterations = static_cast<int>(q.smoothing);
  free_options.elements = q.elements;
  tf_options = free_options;
  tf_options.type = WEFM_MESH_TRANSFINITE;
  tf_options.quads = 1;
  const bool halved = q.elements == WEFM_ELEMENTS_QUADS;  // every face's segments halved (segment_nodes)
  CancelWatcher watcher;
  auto mesh_faces = [&](const std::vector<size_t>& todo) {
    auto work = [&](size_t k) {
      const size_t i = todo[k];
      const bool named = q.transfinite.count(runs[i].face->index) > 0;
      const bool map = named || plan.tubes.count(i) || plan.mapping.faces.count(i);
      wefm_mesh_options options = free_options;
      MappedRequest mapped;
      mapped.options = tf_options;
      options.size = mapped.options.size = plan.face_sizes[i];
      options.split_chords = mapped.options.split_chords = runs[i].split_chords;
      // A face found four-sided (not named, not a tube) keeps only a good grid: the library's
      // automatic meshing judges it, on the corners found here.
      const bool automatic = map && !named && !plan.tubes.count(i);
      if (automatic) mapped.options.type = WEFM_MESH_AUTO;
      mapped.most_elements = automatic ? q.mapped_grid_limit : 0;
      if (const auto c = plan.mapping.sides.find(i); c != plan.mapping.sides.end()) mapped.corner_vertices = c->second.corners;
      mesh_one_face(runs[i], q.settings, q.conformal_first, options, map ? &mapped : nullptr, plan.edge_nodes, watcher);
      return true;
    };
    auto finished = [&](size_t k, size_t done) {
      const FaceMeshRun& r = runs[todo[k]];
      if (!q.quiet)
        std::fprintf(stderr, "[%zu/%zu] f%03d %s: %s (%.2f s)\n", done, todo.size(), r.face->index, r.face->surface_type.c_str(),
                     r.status.c_str(), r.time_solve + r.time_mesh);
    };
    for_each_face(todo.size(), n_threads, work, finished);
  };
  const std::vector<size_t>& source = plan.source;
  auto mesh_or_copy = [&](const std::vector<size_t>& todo) {
    const std::set<size_t> asked(todo.begin(), todo.end());
    std::vector<size_t> own, alone;
    for (size_t i : todo)
      if (!source[i]) own.push_back(i);
    mesh_faces(own);
    for (size_t j = 0; j < runs.size(); ++j)
      if (source[j] && (asked.count(j) || asked.count(source[j] - 1))) {
        reset_run(runs[j], runs[j].edge_refinements);
        if (!copy_coincident(runs[j], runs[source[j] - 1], plan.edge_nodes, weld_tolerance, halved)) alone.push_back(j);
      }
    mesh_faces(alone);
  };
  mesh_or_copy(todo);
  for (int round = 0; round < kEdgeRefinements && !interrupted(); ++round) {
    todo = refine_for_failed_faces(q, model, runs, size, plan);
    if (todo.empty()) break;
    mesh_or_copy(todo);
  }
  for (int round = 0; round < kEdgeNodeAdoptions && !interrupted(); ++round) {
    todo = adopt_edge_nodes(model, runs, plan.edge_nodes, weld_tolerance, source, halved);
    if (todo.empty()) break;
    mesh_or_copy(todo);
  }
}

// The face meshes welded into one, fins dropped, the model edges declared for the conformity check.
// Returns the triangles welding collapsed or dropped.
int64_t assemble(const wefm_cad::CadModel& model, const ModelPlan& plan, const std::vector<FaceMeshRun>& runs, double size, bool halved,
                 ModelMesh& whole) {
  int64_t collapsed = 0;
  for (size_t i = 0; i < runs.size(); ++i)
    if (!runs[i].tris.empty())
      collapsed += whole.add_face(runs[i].face->index, runs[i].xyz, runs[i].tris,
                                  triangle_faces(plan.virtual_faces, i, *runs[i].face, runs[i].xyz, runs[i].tris, size), runs[i].quad_of);
  std::set<std::pair<int, int>> alike;
  for (const FaceMeshRun& r : runs)
    if (r.copy_of) alike.insert({r.copy_of, r.face->index});
  collapsed += whole.drop_fins(alike);
  // Each model edge is used once per edge use in the faces' loops (a seam twice by its face).
  std::map<long long, int> face_uses;
  for (const wefm_cad::CadFace& f : model.faces)
    for (const auto& loop : f.loops)
      for (const wefm_cad::CadEdgeUse& u : loop) ++face_uses[f.edges[static_cast<size_t>(u.edge)].id];
  for (const auto& [id, en] : plan.edge_nodes) whole.expect_model_edge(segment_nodes(en.xyz, halved), face_uses[id]);
  return collapsed;
}

// Wall times of the steps, seconds.
struct MeshModelTimes {
  double total = 0, edges = 0, faces = 0, weld = 0, check = 0, write = 0;
};

// The face meshes welded into `whole` and checked (`conf`), with up to kRepairRounds rounds of
// meshing the faces at fault again (repair_defect_faces) while the check finds defects and every face
// was meshed: the edges around a failed face are open whatever its neighbours do. Returns the
// triangles welding collapsed or dropped; adds to the weld, check and faces times.
int64_t assemble_and_repair(const MeshModelRequest& q, const wefm_cad::CadModel& model, double size, ModelPlan& plan,
                            std::vector<FaceMeshRun>& runs, size_t n_threads, double weld_tolerance, ModelMesh& whole,
                            ConformityCounts& conf, MeshModelTimes& t) {
  for (int round = 0;; ++round) {
    auto t0 = Clock::now();
    whole = ModelMesh(weld_tolerance);
    const int64_t collapsed = assemble(model, plan, runs, size, q.elements == WEFM_ELEMENTS_QUADS, whole);
    t.weld += since(t0);
    t0 = Clock::now();
    conf = whole.conformity();
    t.check += since(t0);
    const bool failed = std::any_of(runs.begin(), runs.end(), [](const FaceMeshRun& r) { return r.status == "failed"; });
    if (!conf.defects() || failed || round == kRepairRounds || interrupted()) return collapsed;
    t0 = Clock::now();
    const std::vector<size_t> todo = repair_defect_faces(q, model, runs, size, plan, conf.defect_faces);
    if (todo.empty()) return collapsed;
    mesh_model_faces(q, model, size, plan, runs, n_threads, weld_tolerance, todo);
    t.faces += since(t0);
  }
}

// The faces meant to be mapped (four-sided or named): how many, meshed transfinite, left free when
// planned (counts not matched, or edges that follow a face lying on another), meshed free at the
// library's say (not four-sided in the domain, the grid refused, or its worst quad below 0.3) or the
// grid limit's; the edges recounted to match; the mapped faces whose opposite sides' counts differ
// in the end.
struct MappedCounts {
  size_t candidates = 0, four_sided = 0, mapped = 0, planned_free = 0, meshed_free = 0, recounted = 0, mismatched = 0;
};

MappedCounts mapped_counts(const ModelPlan& plan, const std::vector<FaceMeshRun>& runs) {
  MappedCounts c;
  c.four_sided = plan.mapping.four_sided;
  c.recounted = plan.mapping.recounted.size();
  for (size_t i = 0; i < runs.size(); ++i) {
    if (!plan.mapping.faces.count(i)) c.planned_free += plan.mapping.refused.count(i);
    else if (runs[i].type == "transfinite") ++c.mapped;
    else ++c.meshed_free;
  }
  c.candidates = c.mapped + c.meshed_free + c.planned_free;
  c.mismatched = mismatched_faces(plan.mapping, plan.edge_nodes);
  return c;
}

// The per-face table, the model line and the failures on stderr. Returns the worst face's exit code.
int print_results(const MeshModelRequest& q, const wefm_cad::CadModel& model, const ModelPlan& plan, const std::vector<FaceMeshRun>& runs,
                  const ModelMesh& whole, const ConformityCounts& conf, const LambdaStats& quality, const ModelMesh::QuadStats& qs,
                  const MeshModelTimes& t, size_t n_threads) {
  std::printf("%-6s %-10s %8s %9s %8s %8s %9s %8s  %s\n", "face", "surface", "elements", "lambda", "min", "<0.6", "score",
              "time", "status");
  int failed = 0, exit_code = kExitOk;
  for (const FaceMeshRun& r : runs) {
    const LambdaStats& fq = r.quality;
    std::printf("f%03d   %-10s %8lld %9.4f %8.4f %7.1f%% %9.4f %7.2fs  %s\n", r.face->index, r.face->surface_type.c_str(),
                static_cast<long long>(fq.triangles), fq.lambda_mesh, fq.lambda_min, 100 * fq.fraction_below_0_6, r.score,
                r.time_solve + r.time_mesh, r.status.c_str());
    if (r.status == "failed") ++failed;
    exit_code = std::max(exit_code, r.exit_code);
  }
  std::printf("model: %lld nodes, %lld triangles, lambda_mesh %.4f, min lambda %.4f, %.1f%% below 0.6; %lld edges, "
              "%lld open, %lld non-manifold (%lld, %lld not explained by the B-rep); %d faces failed; %.2f s (read %.2f, BRepMesh %.2f, edges %.3f, faces %.2f with -j %zu, weld %.2f, check %.2f, write %.2f)\n",
              static_cast<long long>(whole.nodes()), static_cast<long long>(whole.triangles()), quality.lambda_mesh, quality.lambda_min,
              100 * quality.fraction_below_0_6, static_cast<long long>(conf.edges), static_cast<long long>(conf.open_edges),
              static_cast<long long>(conf.non_manifold_edges), static_cast<long long>(conf.unexplained_open_edges),
              static_cast<long long>(conf.unexplained_non_manifold_edges), failed, t.total, model.time_read, model.time_mesh, t.edges,
              t.faces, n_threads, t.weld, t.check, t.write);
  if (q.elements != WEFM_ELEMENTS_TRIANGLES) {
    std::printf("quads: %lld written, %.1f%% of the area; scaled Jacobian min %.4f, mean %.4f (the triangles above are the quads' halves)\n",
                static_cast<long long>(qs.quads), 100 * qs.area_fraction, qs.scaled_jacobian_min, qs.scaled_jacobian_mean);
    // A folded quad is written as it is (the model still conforms) but a solver may refuse it: said
    // even with -q.
    if (qs.folded > 0) {
      std::string where;
      for (size_t k = 0; k < qs.folded_faces.size() && k < 10; ++k) where += (k ? ", f" : "f") + std::to_string(qs.folded_faces[k]);
      if (qs.folded_faces.size() > 10) where += ", ...";
      std::fprintf(stderr, "wefm: warning: %lld quads folded or degenerate (scaled Jacobian 0 or less) on %zu faces (%s)\n",
                   static_cast<long long>(qs.folded), qs.folded_faces.size(), where.c_str());
    }
  }
  if (!plan.mapping.faces.empty() || plan.mapping.four_sided) {
    const MappedCounts m = mapped_counts(plan, runs);
    std::printf("mapped: %zu of %zu faces (%zu four-sided) meshed transfinite; %zu planned free (node counts not matched, or "
                "nodes that follow a face lying on another); %zu meshed free at the library's or the grid limit's say; %zu edges "
                "recounted to match; %zu mapped faces with unlike opposite counts\n",
                m.mapped, m.candidates, m.four_sided, m.planned_free, m.meshed_free, m.recounted, m.mismatched);
  }
  for (const FaceMeshRun& r : runs)
    if (!r.mapped_refused.empty() && q.transfinite.count(r.face->index))
      std::fprintf(stderr, "wefm: %s face %d (%s): meshed free, not transfinite: %s\n", q.model_path.c_str(), r.face->index,
                   r.face->surface_type.c_str(), r.mapped_refused.c_str());
  for (const FaceMeshRun& r : runs)
    if (!r.reason.empty())
      std::fprintf(stderr, "wefm: %s face %d (%s): %s\n", q.model_path.c_str(), r.face->index, r.face->surface_type.c_str(),
                   r.reason.c_str());
  if (conf.defects()) {
    // Not a success: the mesh is written so the defect can be looked at, but the exit says so.
    std::string list;
    for (size_t k = 0; k < conf.defect_faces.size() && k < 20; ++k) list += (k ? ", f" : "f") + std::to_string(conf.defect_faces[k]);
    if (conf.defect_faces.size() > 20) list += ", ...";
    std::fprintf(stderr,
                 "wefm: %s: the mesh does not conform to the model: %lld open and %lld non-manifold edges the B-rep does not "
                 "explain, %lld zero-area triangles (faces %s)\n",
                 q.model_path.c_str(), static_cast<long long>(conf.unexplained_open_edges),
                 static_cast<long long>(conf.unexplained_non_manifold_edges), static_cast<long long>(conf.zero_area_triangles),
                 list.c_str());
    exit_code = std::max<int>(exit_code, kExitSolver);
  }
  return exit_code;
}

// Why a face meant to be mapped (four-sided or named) was meshed free: its counts not matched when
// planned, or the library's or the grid limit's say when meshed; null for the others.
Json mapped_refused(const ModelPlan& plan, const std::vector<FaceMeshRun>& runs, const FaceMeshRun& r) {
  if (!r.mapped_refused.empty()) return r.mapped_refused;
  const auto it = plan.mapping.refused.find(static_cast<size_t>(&r - runs.data()));
  return it != plan.mapping.refused.end() && r.type != "transfinite" ? Json(it->second) : Json(nullptr);
}

Json report_json(const MeshModelRequest& q, const wefm_cad::CadModel& model, const ModelPlan& plan, const std::vector<FaceMeshRun>& runs,
                 const ModelMesh& whole, const ConformityCounts& conf, const LambdaStats& quality, const ModelMesh::QuadStats& qs,
                 int64_t collapsed, const MeshModelTimes& t, size_t n_threads, double size) {
  Json rep;
  rep["model"] = q.model_path;
  rep["size"] = size;
  rep["output"] = q.out_path;
  rep["nodes"] = whole.nodes();
  rep["triangles"] = whole.triangles();
  rep["lambda_mesh"] = quality.lambda_mesh;
  rep["lambda_min"] = quality.lambda_min;
  rep["fraction_below_0_6"] = quality.fraction_below_0_6;
  if (q.elements != WEFM_ELEMENTS_TRIANGLES) {
    // Counts and lambda above are of the triangles the quads were split into (the welded mesh).
    rep["quads"] = {{"quads", qs.quads}, {"area_fraction", qs.area_fraction}, {"scaled_jacobian_min", qs.scaled_jacobian_min},
                    {"scaled_jacobian_mean", qs.scaled_jacobian_mean}, {"folded", qs.folded}, {"folded_faces", qs.folded_faces}};
  }
  const MappedCounts m = mapped_counts(plan, runs);
  rep["mapped"] = {{"candidates", m.candidates}, {"four_sided", m.four_sided}, {"mapped", m.mapped}, {"planned_free", m.planned_free}, {"meshed_free", m.meshed_free},
                   {"recounted_edges", m.recounted}, {"mismatched", m.mismatched}, {"tubes", plan.tubes.size()}};
  rep["bbox_diagonal"] = model.bbox_diagonal;
  rep["conformity"] = {{"edges", conf.edges}, {"open_edges", conf.open_edges}, {"non_manifold_edges", conf.non_manifold_edges},
                       {"brep_edge_segments", conf.brep_edge_segments},
                       {"unexplained_open_edges", conf.unexplained_open_edges},
                       {"unexplained_non_manifold_edges", conf.unexplained_non_manifold_edges},
                       {"zero_area_triangles", conf.zero_area_triangles}, {"defect_faces", conf.defect_faces},
                       {"defect_edges", defect_edges_json(conf)},
                       {"collapsed_triangles", collapsed}};
  rep["timings"] = {{"total", t.total}, {"read", model.time_read}, {"brepmesh", model.time_mesh},
                    {"import", model.time_extract}, {"edges", t.edges}, {"faces_wall", t.faces}, {"jobs", n_threads},
                    {"weld", t.weld}, {"check", t.check}, {"write", t.write}};
  Json faces = Json::array();
  for (const FaceMeshRun& r : runs) {
    const LambdaStats& fq = r.quality;
    faces.push_back({{"face", r.face->index}, {"surface_type", r.face->surface_type}, {"status", r.status},
                     {"reason", r.reason}, {"elements", fq.triangles},
                     {"type", r.type},
                     {"mapped_refused", mapped_refused(plan, runs, r)},
                     {"size", plan.face_sizes[static_cast<size_t>(&r - runs.data())]},
                     {"width", std::isfinite(wefm_cad::face_width(*r.face)) ? Json(wefm_cad::face_width(*r.face)) : Json(nullptr)},
                     {"lambda_mesh", fq.triangles ? Json(fq.lambda_mesh) : Json(nullptr)},
                     {"lambda_min", fq.triangles ? Json(fq.lambda_min) : Json(nullptr)},
                     {"fraction_below_0_6", fq.triangles ? Json(fq.fraction_below_0_6) : Json(nullptr)},
                     {"flatten_score", std::isfinite(r.score) ? Json(r.score) : Json(nullptr)},
                     {"flatten_s", std::isfinite(r.s) ? Json(r.s) : Json(nullptr)},
                     {"conformal_refused", r.conformal_refused.empty() ? Json(nullptr) : Json(r.conformal_refused)},
                     {"flatten_flips", r.flips}, {"edge_refinements", r.edge_refinements}, {"split_chords", r.split_chords},
                     {"flatten_method", r.global_flips >= 0 ? "rollout" : "global"},
                     {"global_flips", r.global_flips >= 0 ? Json(r.global_flips) : Json(nullptr)},
                     {"mesh_of_face", r.copy_of ? Json(r.copy_of) : Json(nullptr)},
                     {"merged_faces", merged_into(plan.virtual_faces, r.face->index)},
                     {"time_flatten", r.time_solve}, {"time_mesh", r.time_mesh}});
    if (q.elements != WEFM_ELEMENTS_TRIANGLES) {
      // The face's quads as the library meshed them (a face lying on another: that face's), before
      // welding re-splits any; "elements" above counts their halves.
      const FaceMeshRun* m = &r;
      if (r.copy_of)
        for (const FaceMeshRun& o : runs)
          if (o.face->index == r.copy_of) m = &o;
      const wefm_mesh_report& mr = m->report;
      Json& f = faces.back();
      f["quads"] = mr.quads;
      f["quad_area_fraction"] = mr.quad_area_fraction;
      f["scaled_jacobian_min"] = mr.quads ? Json(mr.scaled_jacobian_min) : Json(nullptr);
      f["scaled_jacobian_mean"] = mr.quads ? Json(mr.scaled_jacobian_mean) : Json(nullptr);
    }
  }
  rep["faces"] = faces;
  rep["merged_faces"] = merges_json(plan.virtual_faces);
  // Corners where no triangle can reach Lo lambda 0.3, whatever the mesh: a quality check can tell
  // the slivers the geometry forces from those the mesher left.
  Json corners = Json::array();
  for (const FaceMeshRun& r : runs)
    for (const FaceCorner& c : plan.corners[static_cast<size_t>(&r - runs.data())]) {
      const double* x = &r.face->xyz[3 * static_cast<size_t>(c.vertex)];
      corners.push_back({{"face", r.face->index}, {"degrees", c.degrees}, {"point", {x[0], x[1], x[2]}}, {"edges", c.edges}});
    }
  rep["sharp_corners"] = corners;
  return rep;
}

int run_mesh_model(const std::vector<std::string>& argv) {
  MeshModelRequest q;
  if (const int code = parse_request(argv, q); code >= 0) return code;
  const auto t_start = Clock::now();
  std::string error;
  wefm_cad::CadModel model;
  if (const int code = load_cad_model_via_plugin(q.model_path, q.tess, model, error)) {
    std::fprintf(stderr, "wefm: %s\n", error.c_str());
    return code;
  }
  const double size = q.size_is_ratio ? q.size * model.bbox_diagonal : q.size;
  ModelPlan plan;
  if (const int code = plan_model(q, model, size, plan); code >= 0) return code;
  MeshModelTimes t;
  t.edges = plan.time;

  std::vector<FaceMeshRun> runs(model.faces.size());
  for (size_t i = 0; i < runs.size(); ++i) runs[i].face = &model.faces[i];
  const size_t n_threads = std::min<size_t>(static_cast<size_t>(q.jobs), std::max<size_t>(1, runs.size()));
  // Weld at a tolerance far below the size and the facet lengths, far above rounding.
  const double weld_tolerance = 1e-7 * model.bbox_diagonal;
  auto t0 = Clock::now();
  std::vector<size_t> all(runs.size());
  for (size_t i = 0; i < all.size(); ++i) all[i] = i;
  mesh_model_faces(q, model, size, plan, runs, n_threads, weld_tolerance, all);
  t.faces = since(t0);

  ModelMesh whole(weld_tolerance);
  ConformityCounts conf;
  const int64_t collapsed = assemble_and_repair(q, model, size, plan, runs, n_threads, weld_tolerance, whole, conf, t);
  for (FaceMeshRun& r : runs) r.quality = ModelMesh::lambda_of(r.xyz, r.tris);
  t0 = Clock::now();
  const LambdaStats quality = whole.lambda();
  // Quads (with quads asked for): measured once for the printout and the report.
  const ModelMesh::QuadStats quads = q.elements != WEFM_ELEMENTS_TRIANGLES ? whole.quads() : ModelMesh::QuadStats{};
  t.check += since(t0);
  t0 = Clock::now();
  int write_code = kExitOk;
  if (!make_parent_dirs(q.out_path, error) || write_mesh(q.out_path, q.format, whole.description(), error) != kExitOk) {
    std::fprintf(stderr, "wefm: %s\n", error.c_str());
    write_code = kExitIo;
  }
  t.write = since(t0);
  t.total = since(t_start);

  int exit_code = std::max(write_code, print_results(q, model, plan, runs, whole, conf, quality, quads, t, n_threads));
  if (!q.report_path.empty()) {
    const Json rep = report_json(q, model, plan, runs, whole, conf, quality, quads, collapsed, t, n_threads, size);
    if (const int code = write_file_atomically(q.report_path, rep.dump(1) + '\n', error)) {
      std::fprintf(stderr, "wefm: %s\n", error.c_str());
      exit_code = std::max<int>(exit_code, code);
    }
  }
  return exit_after_stop(exit_code, q.model_path);
}

#else  // built without Open CASCADE

int run_mesh_model(const std::vector<std::string>&) {
  std::fprintf(stderr, "wefm mesh-model: this wefm was built without CAD import (WEFM_WITH_OCCT=OFF)\n");
  return kExitIo;
}

#endif

}  // namespace

Command mesh_model_command() {
  return {"mesh-model", "mesh a whole CAD model into one conforming surface mesh (MSH, OBJ, VTK, VTU, PLY)", run_mesh_model};
}

}  // namespace wefm_cli
