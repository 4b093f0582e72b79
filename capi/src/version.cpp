#include "wefm/wefm.h"
#include "wefm/core/linalg/sparse_cholesky.hpp"

#define WEFM_STR2(x) #x
#define WEFM_STR(x) WEFM_STR2(x)

extern "C" {

WEFM_API const char* wefm_version(void) {
  return WEFM_STR(WEFM_VERSION_MAJOR) "." WEFM_STR(WEFM_VERSION_MINOR) "." WEFM_STR(WEFM_VERSION_PATCH);
}

WEFM_API int wefm_version_number(void) { return WEFM_VERSION_NUMBER; }

WEFM_API int wefm_has_suitesparse(void) { return wefm::have_cholmod() ? 1 : 0; }

}
