#include "exit_codes.hpp"

#include "stop.hpp"

namespace wefm_cli {

int exit_code_for(wefm_status status) {
  switch (status) {
    case WEFM_OK: return kExitOk;
    case WEFM_ERROR_IO:
    case WEFM_ERROR_UNSUPPORTED: return kExitIo;
    case WEFM_ERROR_INVALID_MESH:
    case WEFM_ERROR_INVALID_TOPOLOGY:
    case WEFM_ERROR_INVALID_CONSTRAINT: return kExitInvalid;
    case WEFM_ERROR_INVALID_ARGUMENT: return kExitUsage;
    case WEFM_ERROR_CANCELLED: return stop_exit_code();
    default: return kExitSolver;  // singular, not positive definite, not converged, memory, internal
  }
}

const char* exit_codes_help() {
  return "Exit codes:\n"
         "  0  success\n"
         "  2  bad usage (unknown option, bad option value)\n"
         "  3  unreadable input or unwritable output (also an unsupported file format)\n"
         "  4  invalid mesh or topology (seams, --topology file, --edge-mode-of that does not fit)\n"
         "  5  solver or meshing failure, including not converged and a --max-elements refusal (outputs are\n"
         "     still written when a result exists)\n"
         "  6  cancelled (Ctrl-C or SIGTERM; a second one ends the process at once)\n"
         "  7  time limit reached (--time-limit, or the CAD import's own limit)\n"
         "Outputs are replaced whole or not at all: a failed or stopped run leaves the previous file.\n";
}

}  // namespace wefm_cli
