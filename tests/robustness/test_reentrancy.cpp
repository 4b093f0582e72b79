// A face called from inside its own progress callback (wefm.h, "Re-entrancy"): every call that
// would change it is refused with WEFM_ERROR_INVALID_STATE and changes nothing, reads and cancel
// work, and a release of the last reference frees the face only once its solve has returned.
#include <doctest/doctest.h>

#include <functional>
#include <string>
#include <vector>

#include "capi_meshes.hpp"

using namespace wefm_test;

namespace {

struct Reentry {
  std::function<wefm_status(wefm_face*)> call;
  wefm_face* face = nullptr;
  int calls = 0;
  std::vector<wefm_status> statuses;
  std::string message;
};

// Makes the call at the first progress report and at the third (mid-solve).
int call_back(void* user, double, const char*) {
  auto* r = static_cast<Reentry*>(user);
  if (++r->calls == 1 || r->calls == 3) {
    r->statuses.push_back(r->call(r->face));
    if (r->message.empty()) r->message = wefm_face_last_error(r->face);
  }
  return 0;
}

}  // namespace

TEST_CASE("every call that changes a face is refused from inside its own progress callback") {
  const Arrays a = flat(6), other = flat(3);
  std::vector<int64_t> tri64(other.tri.begin(), other.tri.end());
  wefm_mesh* mesh = nullptr;
  REQUIRE(wefm_mesh_create(other.nv(), other.xyz.data(), other.nt(), other.tri.data(), &mesh) == WEFM_OK);
  const wefm_options opts = options();
  wefm_mesh_options mo;
  wefm_mesh_options_init(&mo);
  mo.size = 0.5;
  const int32_t chain[2] = {0, 1}, edges[1] = {0}, pairs[2] = {0, 1}, uses[1] = {0};
  const double coef[2] = {1, 0}, rhs[2] = {5, 5}, nodes[6] = {0, 0, 0, 1, 0, 0};
  const std::vector<std::pair<const char*, std::function<wefm_status(wefm_face*)>>> changes = {
      {"set_mesh", [&](wefm_face* f) { return wefm_face_set_mesh(f, other.nv(), other.xyz.data(), other.nt(), other.tri.data()); }},
      {"set_mesh_i64", [&](wefm_face* f) { return wefm_face_set_mesh_i64(f, other.nv(), other.xyz.data(), other.nt(), tri64.data()); }},
      {"set_mesh_from", [&](wefm_face* f) { return wefm_face_set_mesh_from(f, mesh); }},
      {"set_options", [&](wefm_face* f) { return wefm_face_set_options(f, &opts); }},
      {"clear_topology", [](wefm_face* f) { return wefm_face_clear_topology(f); }},
      {"add_edge", [&](wefm_face* f) { return wefm_face_add_edge(f, 2, chain, nullptr); }},
      {"add_loop", [&](wefm_face* f) { return wefm_face_add_loop(f, 1, edges, nullptr, nullptr); }},
      {"set_outer_loop", [](wefm_face* f) { return wefm_face_set_outer_loop(f, 0); }},
      {"add_seams", [&](wefm_face* f) { return wefm_face_add_seams(f, 1, pairs); }},
      {"set_edge_mode", [](wefm_face* f) { return wefm_face_set_edge_mode(f, 0, WEFM_EDGE_FREE); }},
      {"build", [](wefm_face* f) { return wefm_face_build(f); }},
      {"add_pin", [](wefm_face* f) { return wefm_face_add_pin(f, 0, 5, 5, nullptr); }},
      {"add_constraint", [&](wefm_face* f) { return wefm_face_add_constraint(f, 1, uses, coef, rhs, nullptr); }},
      {"clear_constraints", [](wefm_face* f) { return wefm_face_clear_constraints(f); }},
      {"set_edge_nodes", [&](wefm_face* f) { return wefm_face_set_edge_nodes(f, 0, 2, nodes); }},
      {"clear_edge_nodes", [](wefm_face* f) { return wefm_face_clear_edge_nodes(f); }},
      {"solve", [](wefm_face* f) { return wefm_face_solve(f); }},
      {"mesh_domain",
       [&](wefm_face* f) {
         wefm_domain_mesh* dm = nullptr;
         const wefm_status s = wefm_face_mesh_domain(f, &mo, &dm);
         wefm_domain_mesh_release(dm);
         return s;
       }},
      {"set_progress_callback", [](wefm_face* f) { return wefm_face_set_progress_callback(f, nullptr, nullptr); }},
  };
  for (const auto& [name, call] : changes) {
    CAPTURE(name);
    Face f(a);
    REQUIRE(f.last == WEFM_OK);
    // A first result, so that mesh_domain and the queries of a result have one to work on.
    REQUIRE(wefm_face_solve(f) == WEFM_OK);
    const std::vector<double> before = get_uv(f);
    Reentry r;
    r.call = call;
    r.face = f;
    REQUIRE(wefm_face_set_progress_callback(f, call_back, &r) == WEFM_OK);
    CHECK(wefm_face_solve(f) == WEFM_OK);
    REQUIRE(r.statuses.size() == 2);
    CHECK(r.statuses[0] == WEFM_ERROR_INVALID_STATE);
    CHECK(r.statuses[1] == WEFM_ERROR_INVALID_STATE);
    CHECK(r.message.find(std::string("wefm_face_") + name) != std::string::npos);
    CHECK(r.message.find("progress callback") != std::string::npos);
    // Nothing changed: the same mesh, no constraint, the callback still set (it ran to the end),
    // and the new result is the unconstrained one.
    CHECK(use_count(f) == a.nv());
    CHECK(r.calls > 3);
    CHECK(get_uv(f) == before);
    // After the solve the same call is accepted again (or fails for its own reasons, not state).
    REQUIRE(wefm_face_set_progress_callback(f, nullptr, nullptr) == WEFM_OK);
    const wefm_status after = call(f);
    CHECK(after != WEFM_ERROR_INVALID_STATE);
  }
  wefm_mesh_release(mesh);
}

TEST_CASE("reads and cancel work from inside the progress callback") {
  Face f(flat(6));
  REQUIRE(wefm_face_solve(f) == WEFM_OK);
  Reentry r;
  r.face = f;
  r.call = [](wefm_face* face) {
    int32_t solved = 0;
    int64_t n = 0;
    wefm_options o = options();
    wefm_report rep;
    wefm_report_init(&rep);
    double uv[2] = {0, 0}, xyz[3];
    const wefm_status reads[] = {wefm_face_has_result(face, &solved), wefm_face_get_options(face, &o), wefm_face_use_count(face, &n),
                                 wefm_face_get_uv(face, nullptr, 0, &n), wefm_face_get_report(face, &rep),
                                 wefm_face_map_uv_to_3d(face, 1, uv, xyz, nullptr, nullptr), wefm_face_retain(face)};
    wefm_face_release(face);
    for (wefm_status s : reads)
      if (s != WEFM_OK) return s;
    return solved == 1 ? wefm_face_cancel(face) : WEFM_ERROR_INTERNAL;
  };
  REQUIRE(wefm_face_set_progress_callback(f, call_back, &r) == WEFM_OK);
  CHECK(wefm_face_solve(f) == WEFM_ERROR_CANCELLED);
  REQUIRE(!r.statuses.empty());
  CHECK(r.statuses[0] == WEFM_OK);
}

TEST_CASE("releasing the last reference from the progress callback frees the face after its solve") {
  // Under ASan and valgrind (robust.valgrind_capi runs the same in C) a use after free would be
  // reported; here the solve must complete with its own status.
  wefm_face* f = nullptr;
  REQUIRE(wefm_face_create(&f) == WEFM_OK);
  const Arrays a = flat(6);
  REQUIRE(wefm_face_set_mesh(f, a.nv(), a.xyz.data(), a.nt(), a.tri.data()) == WEFM_OK);
  Reentry r;
  r.face = f;
  // The only reference goes at the first report; at the second the face must still be readable.
  r.call = [&r](wefm_face* face) {
    if (r.statuses.empty()) wefm_face_release(face);
    int64_t n = 0;
    return wefm_face_use_count(face, &n);
  };
  REQUIRE(wefm_face_set_progress_callback(f, call_back, &r) == WEFM_OK);
  CHECK(wefm_face_solve(f) == WEFM_OK);
  REQUIRE(r.statuses.size() == 2);
  CHECK(r.statuses[0] == WEFM_OK);
  CHECK(r.statuses[1] == WEFM_OK);
}
