// libFuzzer target: the mesh readers behind wefm_mesh_read (OBJ, OFF, STL ASCII/binary, PLY). The
// first byte picks the extension, the second the STL merge tolerance; the rest is the file. A mesh
// that reads is queried and, when small, handed to a face and built.
#include <unistd.h>
#include <wefm/wefm.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "fuzz_input.hpp"

using wefm_fuzz::violated;

namespace {

std::string temp_dir() {
  static std::string dir = [] {
    const char* t = std::getenv("TMPDIR");
    std::string tmpl = std::string(t && *t ? t : "/tmp") + "/wefm_fuzz_XXXXXX";
    std::vector<char> buf(tmpl.begin(), tmpl.end());
    buf.push_back('\0');
    if (!mkdtemp(buf.data())) violated("mkdtemp", tmpl.c_str());
    return std::string(buf.data());
  }();
  return dir;
}

std::vector<std::string> created;
void cleanup() {
  for (const auto& p : created) std::remove(p.c_str());
  std::remove(temp_dir().c_str());
}

void check(wefm_status s, const char* where) {
  if (std::strcmp(wefm_status_string(s), "WEFM_ERROR_UNKNOWN") == 0) violated("undocumented status", where);
  if (s == WEFM_ERROR_INTERNAL) violated("WEFM_ERROR_INTERNAL", wefm_last_error());
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 2) return 0;
  static const char* const ext[] = {"obj", "off", "stl", "ply", "OBJ", "Stl"};
  const std::string path = temp_dir() + "/input." + ext[data[0] % 6];
  static bool registered = false;
  if (!registered) {
    registered = true;
    std::atexit(cleanup);
  }
  bool known = false;
  for (const auto& p : created) known = known || p == path;
  if (!known) created.push_back(path);
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) violated("fopen", path.c_str());
  if (size > 2 && std::fwrite(data + 2, 1, size - 2, f) != size - 2) violated("fwrite", path.c_str());
  std::fclose(f);
  const double tol = data[1] < 128 ? data[1] * 1e-6 : -1.0;

  wefm_mesh* m = nullptr;
  const wefm_status s = wefm_mesh_read(path.c_str(), tol, &m);
  check(s, "wefm_mesh_read");
  if ((s == WEFM_OK) != (m != nullptr)) violated("wefm_mesh_read", "handle/status mismatch");
  if (s != WEFM_OK) {
    if (std::strlen(wefm_last_error()) == 0) violated("wefm_mesh_read", "failure without a message");
    return 0;
  }
  wefm_mesh_info info;
  wefm_mesh_info_init(&info);
  check(wefm_mesh_get_info(m, &info), "wefm_mesh_get_info");
  int64_t nx = 0, nt = 0;
  check(wefm_mesh_get_vertices(m, nullptr, 0, &nx), "wefm_mesh_get_vertices");
  check(wefm_mesh_get_triangles(m, nullptr, 0, &nt), "wefm_mesh_get_triangles");
  if (nx != 3 * info.vertices || nt != 3 * info.triangles) violated("mesh counts", "info and getters disagree");
  std::vector<int32_t> tri(static_cast<size_t>(nt));
  check(wefm_mesh_get_triangles(m, tri.data(), nt, &nt), "wefm_mesh_get_triangles");
  for (int32_t v : tri)
    if (v < 0 || v >= info.vertices) violated("reader", "triangle index out of range in a mesh that was read");
  if (info.triangles <= 2000) {
    wefm_face* face = nullptr;
    wefm_face_create(&face);
    const wefm_status fs = wefm_face_set_mesh_from(face, m);
    check(fs, "wefm_face_set_mesh_from");
    if (fs == WEFM_OK) {
      check(wefm_face_build(face), "wefm_face_build");
      if (info.triangles <= 200) {
        wefm_options o;
        wefm_options_init(&o);
        o.max_rho_iterations = 3;
        o.s_step = 0.5;
        check(wefm_face_set_options(face, &o), "wefm_face_set_options");
        check(wefm_face_solve(face), "wefm_face_solve");
      }
    }
    wefm_face_release(face);
  }
  wefm_mesh_release(m);
  return 0;
}
