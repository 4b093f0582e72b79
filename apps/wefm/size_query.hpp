#pragma once
// The C API's two-call protocol for arrays (wefm.h, "size queries"): ask for the count with a NULL
// buffer, then fill a buffer of that size.
#include <cstdint>
#include <vector>

#include "wefm/wefm.h"

namespace wefm_cli {

// `get(buffer, capacity, &count)` twice into `out`; the first failing status, else WEFM_OK.
template <class T, class Getter>
wefm_status fetch(std::vector<T>& out, Getter get) {
  int64_t n = 0;
  const wefm_status st = get(nullptr, 0, &n);
  if (st != WEFM_OK) return st;
  out.assign(static_cast<size_t>(n), T{});
  return n == 0 ? WEFM_OK : get(out.data(), n, &n);
}

}  // namespace wefm_cli
