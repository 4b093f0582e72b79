#pragma once
// Faces for the C API fuzz targets: a small generated grid, cylinder or raw soup with mutations
// (make_mesh), the status check every target applies, and a face solved with iteration caps that
// keep one input to milliseconds (solved_face).
#include <wefm/wefm.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "fuzz_input.hpp"

namespace wefm_fuzz {

struct Mesh {
  std::vector<double> xyz;
  std::vector<int32_t> tri;
  int32_t nv() const { return static_cast<int32_t>(xyz.size() / 3); }
  int32_t nt() const { return static_cast<int32_t>(tri.size() / 3); }
};

inline void check(wefm_status s, wefm_face* f) {
  if (std::strcmp(wefm_status_string(s), "WEFM_ERROR_UNKNOWN") == 0) violated("undocumented status", std::to_string(static_cast<int>(s)).c_str());
  if (s == WEFM_ERROR_INTERNAL) violated("WEFM_ERROR_INTERNAL", f ? wefm_face_last_error(f) : wefm_last_error());
}

// One getter through wefm.h's buffer protocol: the size query, a buffer one short refused with
// WEFM_ERROR_BUFFER_TOO_SMALL and the count, then the fill with the same count. A size query may
// fail with a documented status (nothing is returned) unless `required`; the fill may not.
template <class T, class Get>
std::vector<T> fetch(wefm_face* f, Get get, bool required = false) {
  int64_t count = -1;
  const wefm_status s = get(static_cast<T*>(nullptr), int64_t(0), &count);
  check(s, f);
  if (s != WEFM_OK) {
    if (required) violated("size query", "failed");
    return {};
  }
  if (count < 0 || count > (int64_t(1) << 26)) violated("size query", "count out of range");
  std::vector<T> buf(static_cast<size_t>(count) + 1);
  if (count > 0) {
    int64_t shorter = -1;
    if (get(buf.data(), count - 1, &shorter) != WEFM_ERROR_BUFFER_TOO_SMALL || shorter != count) violated("size query", "short buffer accepted");
  }
  int64_t filled = -1;
  const wefm_status fs = get(buf.data(), count, &filled);
  check(fs, f);
  if (fs != WEFM_OK || filled != count) violated("size query", "the fill failed or its count changed");
  buf.resize(static_cast<size_t>(count));
  return buf;
}

// A (w x h)-cell grid on a bent sheet, then a few mutations of coordinates and indices.
inline Mesh make_mesh(Input& in) {
  Mesh m;
  const uint8_t mode = in.u8();
  if (mode % 4 == 0) {  // raw: anything at all
    const int nv = 3 + in.u8() % 24, nt = 1 + in.u8() % 32;
    for (int i = 0; i < 3 * nv; ++i) m.xyz.push_back(in.number());
    for (int i = 0; i < 3 * nt; ++i) m.tri.push_back(in.index(0, nv));
    return m;
  }
  const int w = 1 + in.u8() % 7, h = 1 + in.u8() % 7;
  const double bend = in.u8() / 64.0;
  const bool closed = mode % 4 == 3 && w >= 3;  // wrap around: an annulus (or a tube)
  const int cols = closed ? w : w + 1;
  for (int j = 0; j <= h; ++j)
    for (int i = 0; i < cols; ++i) {
      const double a = 2 * 3.141592653589793 * i / w;
      if (closed) m.xyz.insert(m.xyz.end(), {std::cos(a), std::sin(a), 0.5 * j});
      else m.xyz.insert(m.xyz.end(), {static_cast<double>(i), static_cast<double>(j), bend * std::sin(i * 0.7) * j});
    }
  auto id = [&](int i, int j) { return static_cast<int32_t>(j * cols + (i % cols)); };
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const bool diag = (in.u8() & 1) != 0;
      if (diag) {
        m.tri.insert(m.tri.end(), {id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j), id(i + 1, j + 1), id(i, j + 1)});
      } else {
        m.tri.insert(m.tri.end(), {id(i, j), id(i + 1, j), id(i, j + 1), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
      }
    }
  const int mutations = in.u8() % 4;
  for (int k = 0; k < mutations; ++k) {
    const uint8_t what = in.u8();
    if (what % 3 == 0 && !m.xyz.empty()) m.xyz[in.u8() % m.xyz.size()] = in.number();
    else if (what % 3 == 1 && !m.tri.empty()) m.tri[in.u8() % m.tri.size()] = in.index(0, m.nv());
    else if (!m.tri.empty()) m.tri.resize(m.tri.size() - 3);  // drop the last triangle
  }
  return m;
}

// A face with a fuzzed mesh and a few fuzzed options, solved once (the solve may fail: callers
// then see WEFM_ERROR_INVALID_STATE from everything that needs a result). Release it.
inline wefm_face* solved_face(Input& in) {
  wefm_face* f = nullptr;
  if (wefm_face_create(&f) != WEFM_OK) violated("wefm_face_create", wefm_last_error());
  const Mesh m = make_mesh(in);
  check(wefm_face_set_mesh(f, m.nv(), m.xyz.data(), m.nt(), m.tri.data()), f);
  wefm_options o;
  wefm_options_init(&o);
  const uint8_t k = in.u8();
  o.s = (k & 3) * 0.5;
  o.method = (k & 4) ? WEFM_METHOD_ROLLOUT : WEFM_METHOD_GLOBAL;
  o.auto_cut = (k & 8) != 0;
  o.max_rho_iterations = 4;
  o.max_rollout_sweeps = 200;
  o.threads = 1;
  check(wefm_face_set_options(f, &o), f);
  check(wefm_face_solve(f), f);
  return f;
}

}  // namespace wefm_fuzz
