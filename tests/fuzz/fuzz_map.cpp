// libFuzzer target: mapping points between a solved face's domain and 3D (wefm_face_map_uv_to_3d,
// wefm_face_map_3d_to_uv) with points near the domain, far away, huge, NaN and infinite.
// Invariants checked (abort = finding): no crash or sanitizer report; the call returns
// WEFM_ERROR_INVALID_ARGUMENT exactly when some point has a non-finite coordinate, else WEFM_OK
// (WEFM_ERROR_INVALID_STATE before a result); per point, a non-finite point gets
// WEFM_ERROR_INVALID_ARGUMENT, NaN outputs and triangle -1, a finite one WEFM_OK with a triangle of
// the face or WEFM_ERROR_OUTSIDE_DOMAIN with -1, and finite outputs; the inputs are unchanged.
#include <wefm/wefm.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "fuzz_faces.hpp"

using wefm_fuzz::check;
using wefm_fuzz::Input;
using wefm_fuzz::violated;

namespace {

// A coordinate near the domain (around its UVs or vertices) or one of the values that break arithmetic.
double coordinate(Input& in, const std::vector<double>& near, size_t width, size_t k) {
  const uint8_t how = in.u8();
  if (how % 4 != 0 || near.empty()) return in.number();
  const size_t i = (in.u8() % (near.size() / width)) * width + k;
  return near[i] + (static_cast<int>(in.u8()) - 128) / 64.0;
}

void map(wefm_face* f, Input& in, bool to_3d, const std::vector<double>& near, int32_t triangles) {
  const size_t wi = to_3d ? 2 : 3, wo = to_3d ? 3 : 2;
  const int64_t n = in.u8() % 17;
  // One spare element each: with n = 0 the arrays are still not NULL (NULL is NULL_ARGUMENT).
  std::vector<double> p(static_cast<size_t>(n) * wi + 1), out(static_cast<size_t>(n) * wo + 1, 0.0);
  for (size_t j = 0; j + 1 < p.size(); ++j) p[j] = coordinate(in, near, wi, j % wi);
  const std::vector<double> copy = p;
  std::vector<int32_t> st(static_cast<size_t>(n) + 1, -7), tri(static_cast<size_t>(n) + 1, -7);
  const bool want = (in.u8() & 1) != 0;
  const wefm_status s = to_3d ? wefm_face_map_uv_to_3d(f, n, p.data(), out.data(), want ? st.data() : nullptr, want ? tri.data() : nullptr)
                              : wefm_face_map_3d_to_uv(f, n, p.data(), out.data(), want ? st.data() : nullptr, want ? tri.data() : nullptr);
  check(s, f);
  if (std::memcmp(p.data(), copy.data(), p.size() * sizeof(double)) != 0) violated("caller array modified", "map points");
  int32_t solved = 0;
  check(wefm_face_has_result(f, &solved), f);
  if (!solved) {
    if (s != WEFM_ERROR_INVALID_STATE) violated("mapping without a result", wefm_status_string(s));
    return;
  }
  bool any_bad = false;
  for (int64_t i = 0; i < n; ++i) {
    bool finite = true;
    for (size_t k = 0; k < wi; ++k) finite = finite && std::isfinite(p[static_cast<size_t>(i) * wi + k]);
    any_bad = any_bad || !finite;
    bool out_finite = true, out_nan = true;
    for (size_t k = 0; k < wo; ++k) {
      out_finite = out_finite && std::isfinite(out[static_cast<size_t>(i) * wo + k]);
      out_nan = out_nan && std::isnan(out[static_cast<size_t>(i) * wo + k]);
    }
    if (finite ? !out_finite : !out_nan) violated("mapped point", finite ? "a finite point mapped to a non-finite one" : "a non-finite point not mapped to NaN");
    if (!want) continue;
    const int32_t ps = st[static_cast<size_t>(i)], t = tri[static_cast<size_t>(i)];
    if (!finite && (ps != WEFM_ERROR_INVALID_ARGUMENT || t != -1)) violated("point status", "a non-finite point");
    if (finite && ps == WEFM_OK && (t < 0 || t >= triangles)) violated("point status", "an inside point without its triangle");
    if (finite && ps == WEFM_ERROR_OUTSIDE_DOMAIN && t != -1) violated("point status", "an outside point with a triangle");
    if (finite && ps != WEFM_OK && ps != WEFM_ERROR_OUTSIDE_DOMAIN) violated("point status", wefm_status_string(static_cast<wefm_status>(ps)));
  }
  if (s != (any_bad ? WEFM_ERROR_INVALID_ARGUMENT : WEFM_OK)) violated("mapping status", wefm_status_string(s));
}

std::vector<double> face_uv(wefm_face* f) {
  int64_t n = 0;
  if (wefm_face_get_uv(f, nullptr, 0, &n) != WEFM_OK) return {};
  std::vector<double> uv(static_cast<size_t>(n));
  check(wefm_face_get_uv(f, uv.data(), n, &n), f);
  return uv;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  Input in(data, size);
  wefm_face* f = wefm_fuzz::solved_face(in);
  const std::vector<double> uv = face_uv(f);
  std::vector<double> xyz(uv.size() / 2 * 3);
  if (!uv.empty()) check(wefm_face_map_uv_to_3d(f, static_cast<int64_t>(uv.size() / 2), uv.data(), xyz.data(), nullptr, nullptr), f);
  int64_t tri_entries = 0;
  check(wefm_face_get_triangle_uses(f, nullptr, 0, &tri_entries), f);
  const int32_t triangles = static_cast<int32_t>(tri_entries / 3);
  for (int round = 0; round < 8 && !in.empty(); ++round) {
    const bool to_3d = (in.u8() & 1) != 0;
    map(f, in, to_3d, to_3d ? uv : xyz, triangles);
  }
  wefm_face_release(f);
  return 0;
}
