#pragma once
// The process settings the tool lets the library change for itself (wefm.h, "Process."): a library
// leaves them to its host, and here the tool is the host.

namespace wefm_cli {

// OpenBLAS's pool at 1 thread for every solve, unless OPENBLAS_NUM_THREADS names the user's own
// count; huge-page advice for the solve's large arrays and SuiteSparse's allocations, unless
// WEFM_HUGE_PAGES=0. What each gains: docs/PERFORMANCE.md, "Process policy".
void opt_in_process_policy();

}  // namespace wefm_cli
