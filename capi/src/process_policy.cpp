// The host's permissions to change settings of the whole process (wefm.h, "Process." and
// wefm_process_policy). Everything is hands off until a key is set.
#include <cstring>
#include <mutex>
#include <string>
#include <type_traits>

#include "handles.hpp"
#include "wefm/core/linalg/sparse_cholesky.hpp"
#include "wefm/core/sys/error.hpp"
#include "wefm/core/sys/huge_pages.hpp"

using wefm::capi::guarded;

namespace {

constexpr std::int64_t kMaxBlasThreads = 1024;

std::string describe(int key, std::int64_t value) {
  return "wefm_set_process_policy: key " + std::to_string(key) + ", value " + std::to_string(value);
}

void require_range(int key, std::int64_t value, std::int64_t max) {
  if (value < 0 || value > max)
    wefm::fail(wefm::Errc::invalid_argument, describe(key, value) + ": the value must be 0 .. " + std::to_string(max));
}

// The key as the integer the caller passed. A C caller may pass any int; in C++ a value outside the
// enum's range must not be read as the enum type, so its bytes are read as its underlying type.
int key_value(const wefm_process_policy& key) {
  std::underlying_type_t<wefm_process_policy> v;
  std::memcpy(&v, &key, sizeof v);
  return static_cast<int>(v);
}

}  // namespace

extern "C" {

WEFM_API wefm_status wefm_set_process_policy(wefm_process_policy key, int64_t value) {
  return guarded(nullptr, [&] {
    // Two hosts' threads setting keys at once apply them one after the other.
    static std::mutex mutex;
    const std::lock_guard<std::mutex> lock(mutex);
    const int k = key_value(key);
    switch (k) {
      case WEFM_PROCESS_BLAS_THREADS:
        require_range(k, value, kMaxBlasThreads);
        if (!wefm::set_solve_blas_threads(static_cast<int>(value)))
          wefm::fail(wefm::Errc::unsupported, describe(k, value) + ": this process has no OpenBLAS (openblas_set_num_threads)");
        return;
      case WEFM_PROCESS_HUGE_PAGES:
        require_range(k, value, 1);
        wefm::set_huge_pages(value == 1);
        return;
    }
    wefm::fail(wefm::Errc::invalid_argument, describe(k, value) + ": unknown key");
  });
}

WEFM_API wefm_status wefm_get_process_policy(wefm_process_policy key, int64_t* value) {
  WEFM_REQUIRE(value, "wefm_get_process_policy");
  return guarded(nullptr, [&] {
    const int k = key_value(key);
    switch (k) {
      case WEFM_PROCESS_BLAS_THREADS:
        *value = wefm::solve_blas_threads();
        return;
      case WEFM_PROCESS_HUGE_PAGES:
        *value = wefm::huge_pages_enabled() ? 1 : 0;
        return;
    }
    wefm::fail(wefm::Errc::invalid_argument, "wefm_get_process_policy: unknown key " + std::to_string(k));
  });
}

}
