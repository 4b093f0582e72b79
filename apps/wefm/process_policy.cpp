#include "process_policy.hpp"

#include <cstdlib>
#include <cstring>

#include "wefm/wefm.h"

namespace wefm_cli {

void opt_in_process_policy() {
  // A build or process without OpenBLAS answers WEFM_ERROR_UNSUPPORTED: nothing to set there.
  const char* blas = std::getenv("OPENBLAS_NUM_THREADS");
  if (!(blas && *blas)) (void)wefm_set_process_policy(WEFM_PROCESS_BLAS_THREADS, 1);
  const char* huge = std::getenv("WEFM_HUGE_PAGES");
  if (!(huge && std::strcmp(huge, "0") == 0)) (void)wefm_set_process_policy(WEFM_PROCESS_HUGE_PAGES, 1);
}

}  // namespace wefm_cli
