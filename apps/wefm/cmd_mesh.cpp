// wefm mesh INPUT --size H -o MESH.obj [--type free|transfinite] [options]: flatten, mesh the domain,
// write the 3D mesh (OBJ, MSH, VTK, VTU or PLY by extension; quads as four-node elements), its 2D
// domain mesh and the quality report.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "owned.hpp"
#include "wefm/common/element_corners.hpp"
#include "wefm/common/lo_lambda.hpp"
#include "command.hpp"
#include "exit_codes.hpp"
#include "flatten_settings.hpp"
#include "mesh_formats.hpp"
#include "names.hpp"
#include "output_file.hpp"
#include "output_paths.hpp"
#include "progress.hpp"
#include "seams_file.hpp"
#include "size_query.hpp"
#include "topology_file.hpp"

namespace wefm_cli {

namespace {

std::vector<OptionSpec> mesh_specs() {
  std::vector<OptionSpec> specs = {
      {"output", 'o', "MESH.obj", "3D mesh to write, format by extension (.obj: v, vt, f triangles or quads; .msh, .vtk, .vtu, .ply) (required)", "", false},
      {"size", 0, "H", "target 3D element size (required)", "", false},
      {"type", 0, "free|transfinite|auto", "free triangles, a transfinite (mapped) mesh on four corners, or transfinite where "
                                           "the domain is four-sided (four corners of 30 to 150 degrees, other turns under 20) "
                                           "and its grid's worst quad has a scaled Jacobian of 0.3 or more, else free", "free", false},
      {"corners", 0, "U0,U1,U2,U3", "transfinite and auto corners: vertex uses on the outer loop (default: the four sharpest; auto: the four it finds)", "",
       false},
      {"triangles", 0, "", "transfinite: split every quad into two triangles", "", false},
      {"elements", 0, "tri|quad-dominant|quad", "free: triangles; quads where pairs of triangles make good ones (scaled Jacobian >= 0.3); or all quads (each element split at its edge midpoints and centre: sides about H / 2; a transfinite grid halved both ways)", "tri", false},
      {"smoothing", 0, "N", "free: smoothing passes kept only where the 3D quality improves (from the fourth, only nodes of elements under lambda 0.6), then up to 3 optimisation passes (0: neither)", "5", false},
      {"min-angle", 0, "DEG", "free: UV angle bound of the circumcentre refinement after the front", "28", false},
      {"corner-angle", 0, "DEG", "loop vertices turning more than this stay boundary nodes", "30", false},
      {"max-elements", 0, "N", "fail rather than exceed this many elements (0 = no cap)", "0", false},
      {"domain-obj", 0, "FILE.obj", "2D domain mesh to write (points u v 0), format by extension; default MESH.domain.EXT (-o's extension)", "", false},
      {"seams", 0, "FILE", "facet edges to cut along: two 0-based vertex indices per line, # comments", "", false},
      {"topology", 0, "FILE.json", "face topology: edges, loops, outer_loop, per-edge mode (topo.json schema)", "",
       false},
      {"report", 0, "FILE.json", "write the JSON mesh report (quality, counts, times)", "", false},
      {"svg", 0, "FILE.svg", "picture of the 2D domain mesh, elements coloured by Lo's lambda in 3D", "", false},
      {"quiet", 'q', "", "no summary; errors still go to stderr", "", false},
  };
  for (auto& s : solver_option_specs()) specs.push_back(s);
  return specs;
}

void print_help() {
  std::printf(
      "Usage: wefm mesh INPUT --size H -o MESH.obj [--type free|transfinite|auto] [options]\n\n"
      "Flattens one face (as wefm flatten, with the same options), meshes the 2D domain at the 3D size H\n"
      "and maps the mesh back to 3D. Free meshes are triangles (frontal-Delaunay placement sized in 3D +\n"
      "smoothing and optimisation judged in 3D), quad-dominant or all quads with --elements; transfinite\n"
      "meshes are quads on four corners (a periodic strip counts); auto chooses transfinite for a four-sided\n"
      "domain.\n\n%s\n"
      "Options:\n%s\n%s",
      mesh_formats_help(), format_options(mesh_specs()).c_str(), exit_codes_help());
}

// MESH.domain.EXT beside MESH.EXT, in the same format (OBJ when -o has no extension).
std::string default_domain_path(const std::string& mesh) {
  const size_t dot = mesh.rfind('.'), slash = mesh.find_last_of("/\\");
  const bool has_ext = dot != std::string::npos && (slash == std::string::npos || dot > slash);
  return has_ext ? mesh.substr(0, dot) + ".domain" + mesh.substr(dot) : mesh + ".domain.obj";
}

struct MeshArrays {
  std::vector<double> uv, xyz;
  std::vector<int32_t> elements;
  int npe = 3;
};

// The 3D mesh: a UV per node (the domain mesh's nodes), one face group.
int write_3d_mesh(const std::string& path, const MeshArrays& m, std::string& error) {
  MeshDescription d;
  d.comments = {"wefm domain mesh: " + std::to_string(m.xyz.size() / 3) + " nodes, " +
                std::to_string(m.elements.size() / static_cast<size_t>(m.npe)) + " elements"};
  d.xyz = m.xyz;
  d.uv = m.uv;
  d.elements = m.elements;
  d.nodes_per_element = m.npe;
  d.digits17 = true;
  return write_mesh(path, d, error);
}

// The 2D domain mesh: points (u, v, 0).
int write_domain_mesh(const std::string& path, const MeshArrays& m, std::string& error) {
  MeshFormat format = MeshFormat::obj;
  if (!mesh_format_of(path, format, error)) return kExitUsage;
  std::vector<double> flat;
  flat.reserve(m.uv.size() / 2 * 3);
  for (size_t i = 0; i + 1 < m.uv.size(); i += 2) flat.insert(flat.end(), {m.uv[i], m.uv[i + 1], 0.0});
  MeshDescription d;
  d.comments = {format == MeshFormat::obj ? "wefm 2D domain mesh: v u v 0" : "wefm 2D domain mesh: points (u, v, 0)"};
  d.xyz = flat;
  d.elements = m.elements;
  d.nodes_per_element = m.npe;
  d.digits17 = true;
  return write_mesh(path, format, d, error);
}

// Corners of the element at e: a quad-dominant mesh's triangle is four nodes, the last -1.
size_t element_corners(const MeshArrays& m, size_t e) { return wefm_common::element_corners(&m.elements[e], m.npe); }

// Lo's lambda of an element in 3D; a quad by its worse half.
double element_lambda(const MeshArrays& m, size_t e) {
  const int32_t* n = &m.elements[e];
  auto X = [&](int k) { return &m.xyz[3 * static_cast<size_t>(n[k])]; };
  double lam = wefm_common::lo_lambda(X(0), X(1), X(2));
  if (element_corners(m, e) == 4) lam = std::min(lam, wefm_common::lo_lambda(X(0), X(2), X(3)));
  return lam;
}

// Red at lambda 0.6 or less to green at 1.
std::string lambda_colour(double lam) {
  const double t = std::min(1.0, std::max(0.0, (lam - 0.6) / 0.4));
  return "rgb(" + std::to_string(static_cast<int>(255 * (1 - t))) + ',' + std::to_string(static_cast<int>(200 * t + 55)) + ",80)";
}

// The colour scale and the counts behind it, to the right of the mesh at x0.
void mesh_svg_legend(std::ostringstream& f, double x0, size_t elements, double lam_min, size_t below) {
  constexpr double top = 40, bar = 200;
  f << "<g id=\"legend\" font-family=\"sans-serif\" font-size=\"12\">\n"
    << "<text x=\"" << x0 << "\" y=\"20\">Lo's lambda in 3D</text>\n";
  constexpr int steps = 8;  // stacked bands: the same colours the elements get
  for (int i = 0; i < steps; ++i) {
    const double lam = 1.0 - 0.4 * (i + 0.5) / steps;
    f << "<rect x=\"" << x0 << "\" y=\"" << top + bar * i / steps << "\" width=\"24\" height=\"" << bar / steps
      << "\" fill=\"" << lambda_colour(lam) << "\"/>\n";
  }
  const char* labels[] = {"1.0", "0.8", "0.6 or less"};
  for (int i = 0; i < 3; ++i)
    f << "<text x=\"" << x0 + 30 << "\" y=\"" << top + bar * i / 2 + 4 << "\">" << labels[i] << "</text>\n";
  char buf[160];
  std::snprintf(buf, sizeof buf, "%zu %s, min lambda %.3f", elements, "elements", lam_min);
  f << "<text x=\"" << x0 << "\" y=\"" << top + bar + 24 << "\">" << buf << "</text>\n";
  std::snprintf(buf, sizeof buf, "%zu below 0.6 (%.2f%%)", below, elements ? 100.0 * static_cast<double>(below) / static_cast<double>(elements) : 0.0);
  f << "<text x=\"" << x0 << "\" y=\"" << top + bar + 42 << "\">" << buf << "</text>\n</g>\n";
}

// The 2D domain mesh, each element coloured by its Lo's lambda in 3D, with a legend.
int write_mesh_svg(const std::string& path, const MeshArrays& m, std::string& error) {
  constexpr double kLegendWidth = 220;
  double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
  for (size_t i = 0; i + 1 < m.uv.size(); i += 2)
    for (int k = 0; k < 2; ++k) lo[k] = std::min(lo[k], m.uv[i + static_cast<size_t>(k)]), hi[k] = std::max(hi[k], m.uv[i + static_cast<size_t>(k)]);
  const double w = std::max(hi[0] - lo[0], 1e-300), h = std::max(hi[1] - lo[1], 1e-300), scale = 1000.0 / std::max(w, h);
  std::ostringstream f;
  f << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << w * scale + 30 + kLegendWidth << "\" height=\""
    << std::max(h * scale + 20, 300.0) << "\">\n";
  const size_t npe = static_cast<size_t>(m.npe);
  double lam_min = 1;
  size_t below = 0;
  for (size_t e = 0; e < m.elements.size(); e += npe) {
    const double lam = element_lambda(m, e);
    lam_min = std::min(lam_min, lam);
    below += lam < 0.6;
    f << "<polygon fill=\"" << lambda_colour(lam) << "\" stroke=\"black\" stroke-width=\"0.3\" points=\"";
    for (size_t k = 0; k < element_corners(m, e); ++k) {
      const size_t v = static_cast<size_t>(m.elements[e + k]);
      f << 10 + (m.uv[2 * v] - lo[0]) * scale << ',' << 10 + (hi[1] - m.uv[2 * v + 1]) * scale << ' ';
    }
    f << "\"/>\n";
  }
  mesh_svg_legend(f, w * scale + 30, m.elements.size() / std::max<size_t>(npe, 1), lam_min, below);
  f << "</svg>\n";
  return write_file_atomically(path, f.str(), error);
}

class MeshRun {
 public:
  // The progress display covers both the solve and the meshing (the library reports the stages
  // "solve" ... and "mesh" through one callback); `show_progress` false keeps only its stop check.
  MeshRun(const FlattenSettings& s, bool show_progress) : s_(s), progress_(show_progress, "") {}
  MeshRun(const MeshRun&) = delete;
  MeshRun& operator=(const MeshRun&) = delete;
  int code = kExitOk;
  std::string error;

  bool fail(int c, std::string m) {
    code = c, error = std::move(m);
    return false;
  }
  std::string face_error() const { return wefm_face_last_error(face_.get()); }

  bool flatten(const std::string& input) {
    wefm_mesh* rm = nullptr;
    const wefm_status st = wefm_mesh_read(input.c_str(), 0.0, &rm);
    mesh_.reset(rm);
    if (st != WEFM_OK) return fail(st == WEFM_ERROR_INVALID_MESH ? kExitInvalid : kExitIo, "cannot read " + input + ": " + wefm_last_error());
    wefm_face* rf = nullptr;
    if (wefm_face_create(&rf) != WEFM_OK) return fail(kExitSolver, wefm_last_error());
    face_.reset(rf);
    wefm_face_set_progress_callback(rf, &Progress::callback, &progress_);
    if (wefm_face_set_mesh_from(rf, rm) != WEFM_OK) return fail(kExitInvalid, input + ": invalid mesh: " + face_error());
    if (wefm_face_set_options(rf, &s_.options) != WEFM_OK) return fail(kExitUsage, "invalid option: " + face_error());
    TopologyFile topo;
    if (!s_.topology_path.empty()) {
      if (const int c = read_topology_file(s_.topology_path, topo, error)) return fail(c, error);
      for (const auto& chain : topo.chains) {
        int32_t id = -1;
        if (wefm_face_add_edge(rf, static_cast<int64_t>(chain.size()), chain.data(), &id) != WEFM_OK)
          return fail(kExitInvalid, s_.topology_path + ": " + face_error());
      }
      for (size_t l = 0; l < topo.loop_edges.size(); ++l) {
        int32_t id = -1;
        if (wefm_face_add_loop(rf, static_cast<int64_t>(topo.loop_edges[l].size()), topo.loop_edges[l].data(), topo.loop_reversed[l].data(), &id) != WEFM_OK)
          return fail(kExitInvalid, s_.topology_path + ": loop " + std::to_string(l) + ": " + face_error());
      }
    }
    if (!s_.seams_path.empty()) {
      std::vector<int32_t> pairs;
      if (const int c = read_seams_file(s_.seams_path, pairs, error)) return fail(c, error);
      if (!pairs.empty() && wefm_face_add_seams(rf, static_cast<int64_t>(pairs.size() / 2), pairs.data()) != WEFM_OK)
        return fail(kExitInvalid, s_.seams_path + ": " + face_error());
    }
    const int outer = s_.has_outer_loop ? s_.outer_loop : topo.outer_loop;
    if (outer >= 0 && wefm_face_set_outer_loop(rf, outer) != WEFM_OK) return fail(kExitInvalid, "outer loop: " + face_error());
    if (wefm_face_build(rf) != WEFM_OK) return fail(kExitInvalid, input + ": invalid topology: " + face_error());
    for (size_t k = 0; k < topo.modes.size(); ++k)
      if (topo.modes[k] >= 0 && wefm_face_set_edge_mode(rf, static_cast<int32_t>(k), topo.modes[k]) != WEFM_OK)
        return fail(kExitInvalid, s_.topology_path + ": mode: " + face_error());
    for (const auto& [edge, mode] : s_.edge_modes) {
      const long long index = s_.topology_path.empty() ? edge : topo.index_of(edge);
      if (index < 0 || index > 2147483647LL || wefm_face_set_edge_mode(rf, static_cast<int32_t>(index), mode) != WEFM_OK)
        return fail(kExitUsage, "--edge-mode-of " + std::to_string(edge) + ": " + face_error());
    }
    if (interrupted()) return fail(stop_exit_code(), input + ": " + stop_reason());
    const auto t0 = Clock::now();
    wefm_status ss;
    {
      WatchedFace watched(&watcher_, rf);
      ss = wefm_face_solve(rf);
    }
    progress_.finish();
    time_solve = since(t0);
    if (ss == WEFM_ERROR_CANCELLED || interrupted()) return fail(stop_exit_code(), input + ": " + stop_reason());
    int32_t has = 0;
    wefm_face_has_result(rf, &has);
    if (ss != WEFM_OK && !(ss == WEFM_ERROR_NOT_CONVERGED && has))
      return fail(kExitSolver, input + ": solve failed: " + face_error() + " [" + wefm_status_string(ss) + "]");
    if (ss == WEFM_ERROR_NOT_CONVERGED) warning = input + ": not converged: " + face_error() + " (meshing the best result)";
    wefm_report_init(&flatten_report, sizeof flatten_report);
    wefm_face_get_report(rf, &flatten_report);
    return true;
  }

  bool mesh(const wefm_mesh_options& o) {
    wefm_domain_mesh* raw = nullptr;
    wefm_status ms;
    {
      WatchedFace watched(&watcher_, face_.get());
      ms = wefm_face_mesh_domain(face_.get(), &o, &raw);
    }
    progress_.finish();
    wefm_face_set_progress_callback(face_.get(), nullptr, nullptr);
    if (ms == WEFM_ERROR_CANCELLED || interrupted()) {
      wefm_domain_mesh_release(raw);
      return fail(stop_exit_code(), "meshing: " + stop_reason());
    }
    if (ms != WEFM_OK) {
      // The options were checked when they were read, so a refusal here is about this face: a
      // domain the mesher cannot take (4), or a mesh over --max-elements or a failed mesher (5,
      // as mesh-model). Never 2: the command line was fine.
      const std::string m = face_error();
      const bool invalid = ms == WEFM_ERROR_UNSUPPORTED || ms == WEFM_ERROR_INVALID_MESH || ms == WEFM_ERROR_INVALID_TOPOLOGY;
      return fail(invalid ? kExitInvalid : kExitSolver, "meshing failed: " + m + " [" + wefm_status_string(ms) + "]");
    }
    dm_.reset(raw);
    wefm_mesh_report_init(&report, sizeof report);
    wefm_domain_mesh_get_report(raw, &report);
    arrays.npe = report.nodes_per_element;
    const bool ok = fetch(arrays.uv, [&](double* b, int64_t c, int64_t* n) { return wefm_domain_mesh_get_uv(raw, b, c, n); }) == WEFM_OK &&
                    fetch(arrays.xyz, [&](double* b, int64_t c, int64_t* n) { return wefm_domain_mesh_get_xyz(raw, b, c, n); }) == WEFM_OK &&
                    fetch(arrays.elements, [&](int32_t* b, int64_t c, int64_t* n) { return wefm_domain_mesh_get_elements(raw, b, c, n); }) == WEFM_OK;
    return ok || fail(kExitSolver, "reading the mesh: " + std::string(wefm_last_error()));
  }

  double time_solve = 0;
  std::string warning;
  wefm_report flatten_report{};
  wefm_mesh_report report{};
  MeshArrays arrays;

 private:
  const FlattenSettings& s_;
  Progress progress_;      // outlives face_, whose callback points at it
  CancelWatcher watcher_;  // calls wefm_face_cancel on a stop request, in the solve and in the meshing
  std::unique_ptr<wefm_mesh, MeshDeleter> mesh_;
  std::unique_ptr<wefm_face, FaceDeleter> face_;
  std::unique_ptr<wefm_domain_mesh, DomainMeshDeleter> dm_;
};

bool parse_mesh_options(const ParsedArgs& args, wefm_mesh_options& o, std::string& error) {
  wefm_mesh_options_init(&o, sizeof o);
  auto dbl = [&](const char* name, double& out) {
    if (!args.has(name) || parse_double(args.value(name), out)) return true;
    error = std::string("--") + name + ": expected a number, got '" + args.value(name) + "'";
    return false;
  };
  auto integer = [&](const char* name, long long& out) {
    if (!args.has(name) || parse_int(args.value(name), out)) return true;
    error = std::string("--") + name + ": expected an integer, got '" + args.value(name) + "'";
    return false;
  };
  long long smoothing = o.smoothing_iterations, cap = o.max_elements;
  if (!dbl("size", o.size) || !dbl("min-angle", o.min_angle_deg) || !dbl("corner-angle", o.corner_angle_deg) ||
      !integer("smoothing", smoothing) || !integer("max-elements", cap))
    return false;
  o.smoothing_iterations = static_cast<int>(smoothing);
  o.max_elements = cap;
  if (args.has("type")) {
    const std::string& t = args.value("type");
    if (t == "free") o.type = WEFM_MESH_FREE;
    else if (t == "transfinite") o.type = WEFM_MESH_TRANSFINITE;
    else if (t == "auto") o.type = WEFM_MESH_AUTO;
    else return error = "--type: expected free, transfinite or auto, got '" + t + "'", false;
  }
  if (args.has("elements")) {
    const std::string& t = args.value("elements");
    if (t == "tri") o.elements = WEFM_ELEMENTS_TRIANGLES;
    else if (t == "quad-dominant") o.elements = WEFM_ELEMENTS_QUAD_DOMINANT;
    else if (t == "quad") o.elements = WEFM_ELEMENTS_QUADS;
    else return error = "--elements: expected tri, quad-dominant or quad, got '" + t + "'", false;
  }
  if (args.has("corners")) {
    std::stringstream ss(args.value("corners"));
    std::string item;
    int k = 0;
    long long v = 0;
    while (std::getline(ss, item, ',')) {
      if (k >= 4 || !parse_int(item, v) || v < 0 || v > 2147483647LL)
        return error = "--corners: expected four vertex uses U0,U1,U2,U3, got '" + args.value("corners") + "'", false;
      o.corners[k++] = static_cast<int32_t>(v);
    }
    if (k != 4) return error = "--corners: expected four vertex uses U0,U1,U2,U3, got '" + args.value("corners") + "'", false;
  }
  o.quads = args.has("triangles") ? 0 : 1;
  return true;
}

struct MeshRequest {
  FlattenSettings settings;
  wefm_mesh_options mesh{};
  std::string input, out, domain, report_path, svg;  // report_path, svg empty: not asked for
  bool quiet = false;
};

// Parses and checks the arguments. Returns -1 to go on, else the exit code (help printed, bad usage).
int parse_request(const std::vector<std::string>& argv, MeshRequest& q) {
  const auto specs = mesh_specs();
  ParsedArgs args;
  std::string error;
  auto usage = [](const std::string& message) {
    std::fprintf(stderr, "wefm mesh: %s\n", message.c_str());
    return kExitUsage;
  };
  FlattenSettings& s = q.settings;
  if (!parse_args(argv, specs, args, error) ||
      (!args.help && (!apply_solver_options(args, s, error) || !parse_mesh_options(args, q.mesh, error))))
    return usage(error + " (see wefm mesh --help)");
  if (args.help) {
    print_help();
    return kExitOk;
  }
  use_all_threads_unless_given(args, s.options);
  if (args.positionals.size() != 1 || !args.has("output") || !args.has("size"))
    return usage(std::string(args.positionals.size() != 1 ? "expected one INPUT" : !args.has("output") ? "missing -o MESH.obj" : "missing --size H") +
                 " (usage: wefm mesh INPUT --size H -o MESH.obj)");
  if (args.has("seams") && args.has("topology"))
    return usage("--seams and --topology exclude each other: put seam edges in the topology");
  auto opt = [&](const char* name) { return args.has(name) ? args.value(name) : std::string(); };
  s.seams_path = opt("seams");
  s.topology_path = opt("topology");
  q.input = args.positionals[0];
  q.out = args.value("output");
  q.domain = args.has("domain-obj") ? args.value("domain-obj") : default_domain_path(q.out);
  q.report_path = opt("report");
  q.svg = opt("svg");
  q.quiet = args.has("quiet");
  MeshFormat format = MeshFormat::obj;
  for (const auto& [name, path] : {std::pair<const char*, const std::string*>{"-o", &q.out}, {"--domain-obj", &q.domain}})
    if (!mesh_format_of(*path, format, error)) return usage(std::string(name) + ": " + error);
  std::vector<NamedPath> outputs = {{"-o", q.out}, {args.has("domain-obj") ? "--domain-obj" : "the domain mesh (-o's .domain.obj)", q.domain}};
  for (const char* name : {"report", "svg"})
    if (args.has(name)) outputs.push_back({std::string("--") + name, args.value(name)});
  if (!check_output_paths({{"input", q.input}, {"--seams", s.seams_path}, {"--topology", s.topology_path}}, outputs, error))
    return usage(error);
  return -1;
}

// The 3D mesh, the domain mesh and the picture (--svg). Returns the exit code.
int write_meshes(const MeshRequest& q, const MeshArrays& m, std::string& error) {
  int code = write_3d_mesh(q.out, m, error);
  if (code == kExitOk) code = write_domain_mesh(q.domain, m, error);
  if (code == kExitOk && !q.svg.empty()) code = write_mesh_svg(q.svg, m, error);
  return code;
}

nlohmann::json report_json(const MeshRequest& q, const MeshRun& run, double t_mesh) {
  const wefm_mesh_report& r = run.report;
  nlohmann::json j;
  j["input"] = q.input;
  j["type"] = r.transfinite ? "transfinite" : "free";
  j["type_asked"] = q.mesh.type == WEFM_MESH_TRANSFINITE ? "transfinite" : q.mesh.type == WEFM_MESH_AUTO ? "auto" : "free";
  if (q.mesh.type == WEFM_MESH_AUTO) {
    // Why auto made a free mesh (null where it made the grid), and the refused grid's worst quad.
    const char* why = automatic_fallback_name(r.automatic_fallback);
    j["automatic_fallback"] = why ? nlohmann::json(why) : nlohmann::json(nullptr);
    if (r.automatic_fallback == WEFM_FALLBACK_POOR_GRID) j["refused_grid_scaled_jacobian_min"] = r.refused_grid_scaled_jacobian_min;
  }
  j["size"] = q.mesh.size;
  j["flatten"] = {{"s", q.settings.options.s}, {"boundary_weight", q.settings.options.boundary_weight},
                  {"score", run.flatten_report.score}, {"converged", run.flatten_report.converged != 0}, {"time", run.time_solve}};
  j["mesh"] = {{"nodes", r.nodes}, {"elements", r.elements}, {"nodes_per_element", r.nodes_per_element},
               {"lambda_mesh", r.lambda_mesh}, {"lambda_min", r.lambda_min}, {"fraction_below_0_6", r.fraction_below_0_6},
               {"scaled_jacobian_min", r.scaled_jacobian_min}, {"scaled_jacobian_mean", r.scaled_jacobian_mean},
               {"quads", r.quads}, {"quad_area_fraction", r.quad_area_fraction},
               {"wiggle_max", r.wiggle_max}, {"wiggle_mean", r.wiggle_mean},
               {"time", {{"boundary", r.time_boundary}, {"mesh", r.time_mesh}, {"smooth", r.time_smooth}, {"map", r.time_map}, {"total", t_mesh}}}};
  j["outputs"] = {{"mesh", q.out}, {"domain_mesh", q.domain}};
  if (!q.svg.empty()) j["outputs"]["svg"] = q.svg;
  if (!run.warning.empty()) j["warning"] = run.warning;
  return j;
}

void print_summary(const MeshRequest& q, const wefm_mesh_report& r) {
  const bool mixed = r.quads > 0 && r.quads < r.elements;
  std::printf("%s: %lld %s, %lld nodes; lambda_mesh %.4f, min %.4f, below 0.6 %.2f%%", q.input.c_str(), static_cast<long long>(r.elements),
              mixed ? "elements" : r.nodes_per_element == 4 ? "quads" : "triangles", static_cast<long long>(r.nodes), r.lambda_mesh,
              r.lambda_min, 100 * r.fraction_below_0_6);
  if (mixed)
    std::printf("; %lld quads, %.1f%% of the area", static_cast<long long>(r.quads), 100 * r.quad_area_fraction);
  if (r.quads > 0) std::printf("; scaled Jacobian min %.4f mean %.4f", r.scaled_jacobian_min, r.scaled_jacobian_mean);
  if (r.transfinite) std::printf("; transfinite, wiggle max %.3g mean %.3g", r.wiggle_max, r.wiggle_mean);
  else if (q.mesh.type == WEFM_MESH_AUTO) std::printf("; free (not four-sided, unlike caller nodes on opposite sides, or a grid below 0.3)");
  std::printf("\n");
}

int run_mesh(const std::vector<std::string>& argv) {
  MeshRequest q;
  if (const int code = parse_request(argv, q); code >= 0) return code;
  std::string error;
  for (const std::string* p : {&q.out, &q.domain, &q.report_path, &q.svg})
    if (!p->empty() && !make_parent_dirs(*p, error)) {
      std::fprintf(stderr, "wefm: %s\n", error.c_str());
      return kExitIo;
    }
  MeshRun run(q.settings, !q.quiet);
  const auto t0 = Clock::now();
  if (!run.flatten(q.input) || !run.mesh(q.mesh)) {
    std::fprintf(stderr, "wefm: %s\n", run.error.c_str());
    return run.code;
  }
  const double t_mesh = since(t0) - run.time_solve;
  if (interrupted()) {
    std::fprintf(stderr, "wefm: %s: %s\n", q.input.c_str(), stop_reason().c_str());
    return stop_exit_code();
  }
  if (const int code = write_meshes(q, run.arrays, error)) {
    std::fprintf(stderr, "wefm: %s\n", error.c_str());
    return code;
  }
  if (!q.report_path.empty()) {
    if (const int code = write_file_atomically(q.report_path, report_json(q, run, t_mesh).dump(2) + '\n', error)) {
      std::fprintf(stderr, "wefm: %s\n", error.c_str());
      return code;
    }
  }
  if (!q.quiet) print_summary(q, run.report);
  if (!run.warning.empty()) {
    std::fprintf(stderr, "wefm: warning: %s\n", run.warning.c_str());
    return kExitSolver;
  }
  return kExitOk;
}

}  // namespace

Command mesh_command() { return {"mesh", "flatten one face, mesh the domain (free or transfinite), write the 3D mesh (OBJ, MSH, VTK, VTU, PLY)", run_mesh}; }

}  // namespace wefm_cli
