#include "names.hpp"

#include "wefm/wefm.h"

namespace wefm_cli {

namespace {
const char* const kEdgeModes[] = {"auto", "free", "periodic", "scar", "rotational"};
}

const char* edge_mode_name(int mode) {
  return mode >= WEFM_EDGE_AUTO && mode <= WEFM_EDGE_ROTATIONAL ? kEdgeModes[mode] : "unknown";
}

bool parse_edge_mode(const std::string& text, int& mode) {
  for (int m = WEFM_EDGE_AUTO; m <= WEFM_EDGE_ROTATIONAL; ++m) {
    if (text == kEdgeModes[m]) {
      mode = m;
      return true;
    }
  }
  return false;
}

const char* method_name(int method) { return method == WEFM_METHOD_ROLLOUT ? "rollout" : "global"; }

const char* solver_name(int solver) {
  switch (solver) {
    case WEFM_SOLVER_CHOLMOD: return "cholmod";
    case WEFM_SOLVER_EIGEN: return "eigen";
    default: return "auto";
  }
}

const char* automatic_fallback_name(int why) {
  switch (why) {
    case WEFM_FALLBACK_NOT_FOUR_SIDED: return "not four-sided";
    case WEFM_FALLBACK_GRID_REFUSED: return "grid refused";
    case WEFM_FALLBACK_POOR_GRID: return "poor grid";
    default: return nullptr;
  }
}

}  // namespace wefm_cli
