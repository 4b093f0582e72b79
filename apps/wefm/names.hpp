#pragma once
// Text names of the library's enums, shared by the option parser, the topology file and the report.
#include <string>

namespace wefm_cli {

const char* edge_mode_name(int mode);      // "auto", "free", "periodic", "scar", "rotational"; "unknown"
bool parse_edge_mode(const std::string& text, int& mode);
const char* method_name(int method);       // "global", "rollout"
const char* solver_name(int solver);       // "auto", "cholmod", "eigen"
// Why WEFM_MESH_AUTO made a free mesh: "not four-sided", "grid refused", "poor grid"; nullptr for
// WEFM_FALLBACK_NONE or a value this build does not know.
const char* automatic_fallback_name(int why);

}  // namespace wefm_cli
