#include "face_job.hpp"

#include <cctype>
#include <chrono>
#include <cstdio>
#include <memory>

#include "domain_picture.hpp"
#include "exit_codes.hpp"
#include "mesh_formats.hpp"
#include "report_output.hpp"
#include "seams_file.hpp"
#include "size_query.hpp"
#include "owned.hpp"
#include "topology_file.hpp"

namespace wefm_cli {

namespace {

// The library names edges by index; with a topology file the user knows them by id, so
// "edge 8" becomes "edge 8 (id 118)".
std::string annotate_edges(const std::string& msg, const std::vector<long long>& ids) {
  if (ids.empty()) return msg;
  std::string out;
  size_t i = 0;
  while (i < msg.size()) {
    const size_t k = msg.find("edge ", i);
    if (k == std::string::npos) break;
    size_t j = k + 5;
    while (j < msg.size() && std::isdigit(static_cast<unsigned char>(msg[j]))) ++j;
    out.append(msg, i, j - i);
    if (j > k + 5 && (k == 0 || !std::isalpha(static_cast<unsigned char>(msg[k - 1])))) {
      const long long e = std::stoll(msg.substr(k + 5, j - k - 5));
      if (e >= 0 && e < static_cast<long long>(ids.size())) out += " (id " + std::to_string(ids[e]) + ")";
    }
    i = j;
  }
  out.append(msg, i, std::string::npos);
  return out;
}

// The layout as a mesh file: the 3D vertices in input order, a UV per vertex use, one face group.
MeshDescription layout_mesh(const FaceJob& job, const FaceSnapshot& snap, MeshFormat format) {
  MeshDescription m;
  m.comments.push_back(std::string("wefm ") + wefm_version() + " flatten of " + job.input);
  if (format == MeshFormat::obj) m.comments.push_back("v: 3D vertices in input order; vt: UV per vertex use; f: vertex/use (1-based)");
  m.xyz = snap.xyz;
  m.uv = snap.uv;
  m.elements = snap.tris;
  if (snap.tri_uses.size() == snap.tris.size()) m.corner_uv = snap.tri_uses;
  m.groups = {{job.face_tag, "face_" + std::to_string(job.face_tag)}};
  return m;
}

int write_layout(const FaceJob& job, const FaceSnapshot& snap, std::string& error) {
  MeshFormat format = MeshFormat::obj;
  if (!mesh_format_of(job.output_mesh, format, error)) return kExitUsage;
  return write_mesh(job.output_mesh, format, layout_mesh(job, snap, format), error);
}

class Runner {
 public:
  Runner(const FaceJob& job, FaceOutcome& out) : job_(job), s_(job.settings), out_(out) {}

  void run() {
    const auto t0 = Clock::now();
    if (read_mesh() && not_stopped() && setup_face() && not_stopped()) {
      out_.time.setup = since(t0) - out_.time.read;
      const auto ts = Clock::now();
      const bool solved = solve();
      out_.time.solve = since(ts);
      if (solved && not_stopped()) {
        const auto tw = Clock::now();
        write_outputs();
        out_.time.write = since(tw);
      }
    }
    out_.time.total = since(t0);
  }

 private:
  bool fail(int code, std::string message) {
    out_.exit_code = code;
    out_.error = std::move(message);
    return false;
  }
  // Polled between stages: reading and setting up a face of millions of triangles takes seconds.
  bool not_stopped() { return !interrupted() || fail(stop_exit_code(), job_.input + ": " + stop_reason()); }
  std::string face_error() const { return wefm_face_last_error(face_.get()); }

  bool read_mesh() {
    const auto t0 = Clock::now();
    wefm_mesh* raw = nullptr;
    const wefm_status st = wefm_mesh_read(job_.input.c_str(), 0.0, &raw);
    mesh_.reset(raw);
    out_.time.read = since(t0);
    if (st != WEFM_OK || !raw) {
      const int code = st == WEFM_ERROR_INVALID_MESH ? kExitInvalid : st == WEFM_ERROR_OUT_OF_MEMORY ? kExitSolver
                                                                                                  : kExitIo;
      return fail(code, "cannot read " + job_.input + ": " + wefm_last_error() + " [" + wefm_status_string(st) + "]");
    }
    FaceSnapshot& snap = out_.snap;
    wefm_mesh_info_init(&snap.info);
    wefm_status g = wefm_mesh_get_info(raw, &snap.info);
    if (g == WEFM_OK)
      g = fetch(snap.xyz, [&](double* b, int64_t c, int64_t* n) { return wefm_mesh_get_vertices(raw, b, c, n); });
    if (g == WEFM_OK)
      g = fetch(snap.tris, [&](int32_t* b, int64_t c, int64_t* n) { return wefm_mesh_get_triangles(raw, b, c, n); });
    if (g != WEFM_OK) return fail(exit_code_for(g), job_.input + ": " + wefm_last_error());
    return true;
  }

  bool setup_face() {
    wefm_face* raw = nullptr;
    if (wefm_face_create(&raw) != WEFM_OK) return fail(kExitSolver, std::string("cannot create a face: ") + wefm_last_error());
    face_.reset(raw);
    if (wefm_face_set_mesh_from(raw, mesh_.get()) != WEFM_OK)
      return fail(kExitInvalid, job_.input + ": invalid mesh: " + face_error());
    if (wefm_face_set_options(raw, &s_.options) != WEFM_OK)
      return fail(kExitUsage, "invalid option: " + face_error());
    return add_topology() && add_seams() && build() && set_edge_modes() && take_topology();
  }

  bool add_topology() {
    if (s_.topology_path.empty()) return true;
    std::string error;
    if (const int code = read_topology_file(s_.topology_path, topo_, error)) return fail(code, error);
    const std::string& path = s_.topology_path;
    for (size_t k = 0; k < topo_.chains.size(); ++k) {
      const auto& chain = topo_.chains[k];
      int32_t id = -1;
      if (wefm_face_add_edge(face_.get(), static_cast<int64_t>(chain.size()), chain.data(), &id) != WEFM_OK)
        return fail(kExitInvalid, path + ": edge #" + std::to_string(k) + " (id " + std::to_string(topo_.ids[k]) +
                                      "): " + face_error());
    }
    for (size_t l = 0; l < topo_.loop_edges.size(); ++l) {
      int32_t id = -1;
      if (wefm_face_add_loop(face_.get(), static_cast<int64_t>(topo_.loop_edges[l].size()), topo_.loop_edges[l].data(),
                             topo_.loop_reversed[l].data(), &id) != WEFM_OK)
        return fail(kExitInvalid, path + ": loop " + std::to_string(l) + ": " + annotate_edges(face_error(), topo_.ids));
    }
    const int outer = s_.has_outer_loop ? s_.outer_loop : topo_.outer_loop;
    if ((s_.has_outer_loop || outer >= 0) && wefm_face_set_outer_loop(face_.get(), outer) != WEFM_OK)
      return fail(s_.has_outer_loop ? kExitUsage : kExitInvalid,
                  (s_.has_outer_loop ? std::string("--outer-loop: ") : path + ": outer_loop: ") + face_error());
    requested_.assign(topo_.chains.size(), -1);
    for (size_t k = 0; k < topo_.modes.size(); ++k) requested_[k] = topo_.modes[k];
    return true;
  }

  bool add_seams() {
    if (!s_.seams_path.empty()) {
      std::vector<int32_t> pairs;
      std::string error;
      if (const int code = read_seams_file(s_.seams_path, pairs, error)) return fail(code, error);
      if (!pairs.empty() && wefm_face_add_seams(face_.get(), static_cast<int64_t>(pairs.size() / 2), pairs.data()) != WEFM_OK)
        return fail(kExitInvalid, s_.seams_path + ": " + face_error());
    }
    if (s_.topology_path.empty() && s_.has_outer_loop && wefm_face_set_outer_loop(face_.get(), s_.outer_loop) != WEFM_OK)
      return fail(kExitUsage, "--outer-loop: " + face_error());
    return true;
  }

  // Validates the topology now, so its errors are reported as such (exit 4) before any solving.
  bool build() {
    if (wefm_face_build(face_.get()) == WEFM_OK) return true;
    std::string where = !s_.topology_path.empty() ? s_.topology_path : !s_.seams_path.empty() ? s_.seams_path : job_.input;
    return fail(kExitInvalid, where + ": invalid topology: " + annotate_edges(face_error(), topo_.ids));
  }

  // After build, because derived edges (no topology file) only get their indices there.
  bool set_edge_modes() {
    for (size_t k = 0; k < topo_.modes.size(); ++k) {
      if (topo_.modes[k] >= 0 && wefm_face_set_edge_mode(face_.get(), static_cast<int32_t>(k), topo_.modes[k]) != WEFM_OK)
        return fail(kExitInvalid, s_.topology_path + ": edge id " + std::to_string(topo_.ids[k]) + ": mode: " + face_error());
    }
    for (const auto& [edge, mode] : s_.edge_modes) {
      long long index = edge;
      if (!s_.topology_path.empty()) {
        index = topo_.index_of(edge);
        if (index < 0)
          return fail(kExitUsage, "--edge-mode-of: no edge with id " + std::to_string(edge) + " in " + s_.topology_path);
      }
      if (index < 0 || index > 2147483647LL ||
          wefm_face_set_edge_mode(face_.get(), static_cast<int32_t>(index), mode) != WEFM_OK)
        return fail(kExitUsage, "--edge-mode-of " + std::to_string(edge) + ": " + face_error());
      if (static_cast<size_t>(index) >= requested_.size()) requested_.resize(static_cast<size_t>(index) + 1, -1);
      requested_[static_cast<size_t>(index)] = mode;
    }
    return true;
  }

  bool take_topology() {
    if (snapshot_topology(face_.get(), topo_.ids, out_.snap) != WEFM_OK)
      return fail(kExitInvalid, job_.input + ": topology: " + face_error());
    out_.topology_built = true;
    return true;
  }

  bool solve() {
    Progress progress(job_.show_progress, job_.progress_prefix);
    wefm_face_set_progress_callback(face_.get(), &Progress::callback, &progress);
    wefm_status st;
    {
      WatchedFace watched(job_.watcher, face_.get());
      st = wefm_face_solve(face_.get());
    }
    progress.finish();
    wefm_face_set_progress_callback(face_.get(), nullptr, nullptr);
    if (st == WEFM_ERROR_CANCELLED || interrupted()) return fail(stop_exit_code(), job_.input + ": " + stop_reason());
    if (st != WEFM_OK && st != WEFM_ERROR_NOT_CONVERGED) {
      const int code = exit_code_for(st) == kExitInvalid ? kExitInvalid : kExitSolver;
      return fail(code, job_.input + ": solve failed: " + annotate_edges(face_error(), topo_.ids) + " [" +
                            wefm_status_string(st) + "]");
    }
    if (snapshot_result(face_.get(), requested_, s_.options.default_edge_mode, out_.snap) != WEFM_OK)
      return fail(kExitSolver, job_.input + ": reading the result: " + face_error());
    const double s_asked = s_.options.s, s_got = out_.snap.report.s;
    if (out_.snap.has_result && s_asked > 0 && s_got < s_asked - 1e-12) {
      // A valid layout at a smaller s beats an invalid one at the s asked; say so, it is not what was asked.
      char buf[160];
      std::snprintf(buf, sizeof buf, ": the layout written is at s = %g: no valid layout was reached at s = %g", s_got, s_asked);
      out_.warnings.push_back(job_.input + buf);
    }
    if (st == WEFM_ERROR_NOT_CONVERGED) {
      const std::string msg = job_.input + ": not converged: " + face_error();
      if (!out_.snap.has_result) return fail(kExitSolver, msg);
      // The best result is kept: still worth writing, but the exit code must say it is not final.
      out_.exit_code = kExitSolver;
      out_.error = msg + " (outputs written from the best result)";
    }
    return out_.snap.has_result || fail(kExitSolver, job_.input + ": the solve left no result");
  }

  void write_outputs() {
    std::string error;
    auto done = [&](int code, const char* what, const std::string& path) {
      if (code == kExitOk) {
        out_.outputs.emplace_back(what, path);
        return true;
      }
      out_.exit_code = code;
      out_.error = error;
      return false;
    };
    const FaceSnapshot& snap = out_.snap;
    if (!job_.output_mesh.empty() && !done(write_layout(job_, snap, error), "uv mesh", job_.output_mesh)) return;
    if (!s_.svg_path.empty() && !done(write_domain_picture(s_.svg_path, snap, error), "domain picture", s_.svg_path))
      return;
    if (!s_.write_topology_path.empty() &&
        !done(write_topology_file(s_.write_topology_path, snap.topology, error), "topology", s_.write_topology_path))
      return;
    if (!s_.report_path.empty()) {
      ReportContext ctx{job_.input, out_.outputs, out_.exit_code, out_.error, out_.time, out_.warnings};
      ctx.threads = s_.options.threads;
      ctx.timings.total = ctx.timings.read + ctx.timings.setup + ctx.timings.solve;  // writing not yet done
      if (!done(write_report_json(s_.report_path, ctx, snap, error), "report", s_.report_path)) return;
    }
  }

  const FaceJob& job_;
  const FlattenSettings& s_;
  FaceOutcome& out_;
  std::unique_ptr<wefm_mesh, MeshDeleter> mesh_;
  std::unique_ptr<wefm_face, FaceDeleter> face_;
  TopologyFile topo_;
  std::vector<int> requested_;
};

}  // namespace

FaceOutcome run_face_job(const FaceJob& job) {
  FaceOutcome out;
  Runner(job, out).run();
  return out;
}

}  // namespace wefm_cli
