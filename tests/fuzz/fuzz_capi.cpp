// libFuzzer target: the C API driven by arbitrary bytes. A face gets a mesh (a generated grid with
// mutations, or raw vertices and indices), options, then a sequence of topology, seam, constraint,
// solve and query calls. Iteration caps are clamped so one input runs in milliseconds.
// Invariants checked (abort = finding): no crash/sanitizer report, every status is a documented
// code other than WEFM_ERROR_INTERNAL, every OK or NOT_CONVERGED solve leaves finite UVs, the size
// query protocol holds, and the caller's arrays are unchanged by every call.
#include <wefm/wefm.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "fuzz_faces.hpp"

using wefm_fuzz::check;
using wefm_fuzz::fetch;
using wefm_fuzz::Input;
using wefm_fuzz::make_mesh;
using wefm_fuzz::Mesh;
using wefm_fuzz::violated;

namespace {

void set_mesh(wefm_face* f, Input& in) {
  Mesh m = make_mesh(in);
  const Mesh copy = m;
  const uint8_t how = in.u8() % 3;
  if (how == 0) {
    check(wefm_face_set_mesh(f, m.nv(), m.xyz.data(), m.nt(), m.tri.data()), f);
  } else if (how == 1) {
    std::vector<int64_t> t64(m.tri.begin(), m.tri.end());
    if (!t64.empty() && (in.u8() & 7) == 0) t64[0] += int64_t(1) << 32;
    const std::vector<int64_t> c64 = t64;
    check(wefm_face_set_mesh_i64(f, m.nv(), m.xyz.data(), m.nt(), t64.data()), f);
    if (t64 != c64) violated("caller array modified", "set_mesh_i64 triangles");
  } else {
    wefm_mesh* mh = nullptr;
    const wefm_status s = wefm_mesh_create(m.nv(), m.xyz.data(), m.nt(), m.tri.data(), &mh);
    check(s, nullptr);
    if ((s == WEFM_OK) != (mh != nullptr)) violated("wefm_mesh_create", "handle/status mismatch");
    if (mh) {
      check(wefm_mesh_retain(mh), nullptr);  // a second reference, dropped at once: the mesh stays
      wefm_mesh_release(mh);
      wefm_mesh_info info;
      wefm_mesh_info_init(&info);
      check(wefm_mesh_get_info(mh, &info), nullptr);
      check(wefm_face_set_mesh_from(f, mh), f);
      wefm_mesh_release(mh);
    }
  }
  if (m.tri != copy.tri || std::memcmp(m.xyz.data(), copy.xyz.data(), m.xyz.size() * sizeof(double)) != 0)
    violated("caller array modified", "set_mesh");
}

void set_options(wefm_face* f, Input& in) {
  wefm_options o;
  wefm_options_init(&o);
  const int n = in.u8() % 5;
  for (int k = 0; k < n; ++k) {
    const uint8_t field = in.u8() % 19;
    switch (field) {
      case 0: o.s = in.number(); break;
      case 1: o.k = in.number(); break;
      case 2: o.boundary_weight = in.number(); break;
      case 3: o.curvature_adjust = in.u8() & 1; break;
      case 4: o.method = in.index(0, 2); break;
      case 5: o.solver = in.index(0, 3); break;
      case 6: o.default_edge_mode = in.index(0, 5); break;
      case 7: o.s_step = in.number(); break;
      case 8: o.rho_tolerance = in.number(); break;
      case 9: o.max_rho_iterations = in.index(0, 4); break;
      case 10: o.rollout_tolerance = in.number(); break;
      case 11: o.max_rollout_sweeps = in.index(0, 200); break;
      case 12: o.score_threshold = in.number(); break;
      case 13: o.auto_cut = in.u8() & 1; break;
      case 14: o.threads = in.index(0, 3); break;
      case 15: o.memory_limit_mb = in.number(); break;
      case 16: o.min_beta = in.number(); break;
      case 17: o.struct_size = in.u8() % 2 ? 0 : sizeof(size_t) + in.u8(); break;  // old/odd callers
      default: o.s = 0; break;
    }
  }
  // Keep each input fast: few rho iterations and sweeps, coarse continuation steps.
  if (o.max_rho_iterations > 4) o.max_rho_iterations = 4;
  if (o.max_rollout_sweeps > 200) o.max_rollout_sweeps = 200;
  if (o.s_step > 0 && o.s_step < 0.25) o.s_step = 0.25;
  if (o.threads > 2) o.threads = 2;
  const wefm_options copy = o;
  const wefm_status s = wefm_face_set_options(f, &o);
  check(s, f);
  if (std::memcmp(&o, &copy, sizeof o) != 0) violated("caller struct modified", "set_options");
  if (s != WEFM_OK) {  // keep inputs fast even when these options were rejected
    wefm_options_init(&o);
    o.max_rho_iterations = 4;
    o.max_rollout_sweeps = 200;
    check(wefm_face_set_options(f, &o), f);
  }
}

struct Cancel {
  int calls = 0, after = -1;
  wefm_face* face = nullptr;
  int reenter = 0;  // which call the callback makes into its own face (0: none)
};

// A call from inside the progress callback into the solving face: changes must be refused with
// WEFM_ERROR_INVALID_STATE (wefm.h, "Re-entrancy"), reads and a balanced retain/release accepted.
void reenter(Cancel& c) {
  wefm_face* f = c.face;
  wefm_status s = WEFM_OK;
  bool change = true;
  switch (c.reenter % 8) {
    case 1: s = wefm_face_add_pin(f, 0, 1, 1, nullptr); break;
    case 2: s = wefm_face_clear_topology(f); break;
    case 3: s = wefm_face_solve(f); break;
    case 4: {
      const double xyz[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
      const int32_t tri[3] = {0, 1, 2};
      s = wefm_face_set_mesh(f, 3, xyz, 1, tri);
      break;
    }
    case 5: s = wefm_face_clear_constraints(f); break;
    case 6: {
      change = false;
      int32_t solved = 0;
      s = wefm_face_retain(f);
      wefm_face_release(f);
      if (s == WEFM_OK) s = wefm_face_has_result(f, &solved);
      break;
    }
    default: {
      change = false;
      wefm_options o;
      wefm_options_init(&o);
      s = wefm_face_get_options(f, &o);
      break;
    }
  }
  if (change && s != WEFM_ERROR_INVALID_STATE) violated("a change from inside the progress callback was not refused", wefm_status_string(s));
  if (!change && s != WEFM_OK) violated("a read from inside the progress callback failed", wefm_face_last_error(f));
}

int progress(void* user, double fraction, const char* stage) {
  auto* c = static_cast<Cancel*>(user);
  if (!(fraction >= 0 && fraction <= 1)) violated("progress fraction outside [0,1]", stage);
  if (!stage) violated("progress", "NULL stage");
  if (c->reenter) reenter(*c);
  return c->after >= 0 && ++c->calls >= c->after;
}

void solve(wefm_face* f, Input& in) {
  Cancel c;
  c.after = in.u8() % 4 == 0 ? in.u8() % 12 : -1;
  c.face = f;
  c.reenter = in.u8() % 4 == 0 ? 1 + in.u8() % 7 : 0;
  check(wefm_face_set_progress_callback(f, progress, &c), f);
  int32_t before = 0;
  wefm_face_has_result(f, &before);
  const wefm_status s = wefm_face_solve(f);
  check(s, f);
  int32_t solved = 0;
  check(wefm_face_has_result(f, &solved), f);
  if ((s == WEFM_OK || s == WEFM_ERROR_NOT_CONVERGED) && !solved) violated("solve", "success without a result");
  if (s != WEFM_OK && s != WEFM_ERROR_NOT_CONVERGED && solved != before) violated("solve", "a failed solve changed has_result");
  if (s == WEFM_OK || s == WEFM_ERROR_NOT_CONVERGED) {
    int64_t n = 0;
    check(wefm_face_get_uv(f, nullptr, 0, &n), f);
    std::vector<double> uv(static_cast<size_t>(n));
    check(wefm_face_get_uv(f, uv.data(), n, &n), f);
    for (double x : uv)
      if (!std::isfinite(x)) violated("solve returned a non-finite UV", wefm_status_string(s));
  }
  check(wefm_face_set_progress_callback(f, nullptr, nullptr), f);
}

void queries(wefm_face* f, Input& in) {
  int64_t n = 0;
  check(wefm_face_edge_count(f, &n), f);
  check(wefm_face_loop_count(f, &n), f);
  check(wefm_face_use_count(f, &n), f);
  int32_t l = 0;
  check(wefm_face_outer_loop(f, &l), f);
  const int32_t e = in.index(0, 6), lp = in.index(0, 4), v = in.index(0, 40);
  fetch<int32_t>(f, [&](int32_t* b, int64_t c, int64_t* k) { return wefm_face_get_edge(f, e, b, c, k); });
  int32_t rep = 0;
  check(wefm_face_edge_is_repeated(f, e, &rep), f);
  fetch<int32_t>(f, [&](int32_t* b, int64_t c, int64_t* k) { return wefm_face_get_loop(f, lp, b, c, k); });
  fetch<int32_t>(f, [&](int32_t* b, int64_t c, int64_t* k) { return wefm_face_get_loop_uses(f, lp, b, c, k); });
  fetch<int32_t>(f, [&](int32_t* b, int64_t c, int64_t* k) { return wefm_face_get_use_vertices(f, b, c, k); });
  fetch<int32_t>(f, [&](int32_t* b, int64_t c, int64_t* k) { return wefm_face_get_triangle_uses(f, b, c, k); });
  fetch<int32_t>(f, [&](int32_t* b, int64_t c, int64_t* k) { return wefm_face_get_vertex_uses(f, v, b, c, k); });
  fetch<double>(f, [&](double* b, int64_t c, int64_t* k) { return wefm_face_get_uv(f, b, c, k); });
  fetch<int32_t>(f, [&](int32_t* b, int64_t c, int64_t* k) { return wefm_face_get_edge_modes(f, b, c, k); });
  fetch<double>(f, [&](double* b, int64_t c, int64_t* k) { return wefm_face_get_edge_scores(f, e, b, c, k); });
  fetch<double>(f, [&](double* b, int64_t c, int64_t* k) { return wefm_face_get_step_history(f, b, c, k); });
  wefm_report r;
  wefm_report_init(&r);
  if (in.u8() % 8 == 0) r.struct_size = sizeof(size_t) + in.u8() % 64;  // an older, smaller struct
  check(wefm_face_get_report(f, &r), f);
}

// The process policies are the host's (wefm.h, "Process."): only refusals are fuzzed, since an
// accepted value would change the fuzzer's own process, and a refusal must change nothing.
void refused_process_policy(Input& in) {
  const auto key = static_cast<wefm_process_policy>(in.u8() % 4);  // 0 and 3 are no key
  int64_t before = 0, after = 0;
  const bool known = wefm_get_process_policy(key, &before) == WEFM_OK;
  if (wefm_set_process_policy(key, -1 - static_cast<int64_t>(in.u8())) != WEFM_ERROR_INVALID_ARGUMENT)
    violated("wefm_set_process_policy", "a negative value was accepted");
  if (known && (wefm_get_process_policy(key, &after) != WEFM_OK || after != before))
    violated("wefm_set_process_policy", "a refused value changed the policy");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  Input in(data, size);
  if (wefm_version_number() != WEFM_VERSION_NUMBER || !wefm_version()) violated("version", "the library and its header differ");
  (void)wefm_has_suitesparse();  // a property of the build: called so that every export is reached
  wefm_face* f = nullptr;
  if (wefm_face_create(&f) != WEFM_OK) violated("wefm_face_create", wefm_last_error());
  set_mesh(f, in);
  set_options(f, in);
  for (int step = 0; step < 24 && !in.empty(); ++step) {
    const uint8_t op = in.u8() % 18;
    switch (op) {
      case 0: {
        std::vector<int32_t> ch(1 + in.u8() % 8);
        for (auto& x : ch) x = in.index(0, 40);
        const auto copy = ch;
        int32_t id = -1;
        check(wefm_face_add_edge(f, in.u8() % 4 == 0 ? -1 : static_cast<int64_t>(ch.size()), ch.data(), &id), f);
        if (ch != copy) violated("caller array modified", "add_edge");
        break;
      }
      case 1: {
        const size_t n = 1 + in.u8() % 6;
        std::vector<int32_t> edges(n), rev(n);
        for (size_t j = 0; j < n; ++j) {
          edges[j] = in.index(0, 6);
          rev[j] = in.u8() & 1;
        }
        int32_t id = -1;
        check(wefm_face_add_loop(f, static_cast<int64_t>(n), edges.data(), in.u8() & 1 ? rev.data() : nullptr, &id), f);
        break;
      }
      case 2: {
        std::vector<int32_t> pairs(2 * (1 + in.u8() % 6));
        for (auto& x : pairs) x = in.index(0, 40);
        const auto copy = pairs;
        check(wefm_face_add_seams(f, static_cast<int64_t>(pairs.size() / 2), pairs.data()), f);
        if (pairs != copy) violated("caller array modified", "add_seams");
        break;
      }
      case 3: check(wefm_face_set_outer_loop(f, in.index(-1, 4)), f); break;
      case 4: check(wefm_face_set_edge_mode(f, in.index(0, 6), in.index(0, 5)), f); break;
      case 5: {
        int32_t id = -1;
        const int32_t use = in.index(0, 40);
        const double u = in.number(), v = in.number();
        check(wefm_face_add_pin(f, use, u, v, &id), f);
        break;
      }
      case 6: {
        const size_t n = in.u8() % 4;
        std::vector<int32_t> uses(n + 1);
        std::vector<double> coef(2 * n + 2), rhs(2);
        for (auto& x : uses) x = in.index(0, 40);
        for (auto& x : coef) x = in.number();
        for (auto& x : rhs) x = in.number();
        const auto cu = uses;
        const auto cc = coef;
        int32_t id = -1;
        check(wefm_face_add_constraint(f, static_cast<int64_t>(n), uses.data(), coef.data(), rhs.data(), &id), f);
        if (uses != cu || std::memcmp(coef.data(), cc.data(), coef.size() * sizeof(double)) != 0) violated("caller array modified", "add_constraint");
        break;
      }
      case 7: check(wefm_face_clear_topology(f), f); break;
      case 8: check(wefm_face_clear_constraints(f), f); break;
      case 9: check(wefm_face_build(f), f); break;
      case 10:
      case 11: solve(f, in); break;
      case 12: queries(f, in); break;
      case 13: set_options(f, in); break;
      case 14: check(wefm_face_cancel(f), f); break;
      case 15: set_mesh(f, in); break;
      case 16: {
        wefm_face* g = nullptr;  // a second reference, released at once: the face must survive
        check(wefm_face_retain(f), f);
        g = f;
        wefm_face_release(g);
        break;
      }
      default: check(wefm_face_write_obj(f, "/dev/null"), f); break;
    }
  }
  wefm_face_release(f);
  refused_process_policy(in);  // last: the corpus's bytes keep their meaning for the calls above
  return 0;
}
