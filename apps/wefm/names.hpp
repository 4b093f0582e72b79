#pragma once
// Text names of the library's enums, shared by the option parser, the topology file and the report.
#include <string>

namespace wefm_cli {

const char* edge_mode_name(int mode);      // "auto", "free", "periodic", "scar", "rotational"; "unknown"
bool parse_edge_mode(const std::string& text, int& mode);
const char* method_name(int method);       // "global", "rollout"
const char* solver_name(int solver);       // "auto", "cholmod", "eigen"

}  // namespace wefm_cli
