#pragma once
// Everything `wefm flatten` (and `wefm batch`, which flattens many faces the same way) takes from the
// command line. The solver options map one-to-one onto wefm_options; their defaults are read from
// wefm_options_init at run time so --help never disagrees with the library.
#include <string>
#include <utility>
#include <vector>

#include "args.hpp"
#include "wefm/wefm.h"

namespace wefm_cli {

struct FlattenSettings {
  wefm_options options{};
  std::vector<std::pair<long long, int>> edge_modes;  // --edge-mode-of EDGE=MODE
  bool has_outer_loop = false;
  int outer_loop = -1;
  std::string seams_path;            // --seams
  std::string topology_path;         // --topology
  std::string write_topology_path;   // --write-topology
  std::string report_path;           // --report
  std::string svg_path;              // --svg (.svg or .png)
  bool quiet = false;
};

// The wefm_options options (shared by flatten and batch).
std::vector<OptionSpec> solver_option_specs();

// Fills settings.options and edge_modes/outer_loop from parsed solver options. False + error on a
// malformed value (exit code 2). --time-limit starts the deadline (stop.hpp) here.
bool apply_solver_options(const ParsedArgs& args, FlattenSettings& settings, std::string& error);

// The commands that solve one face at a time (flatten, mesh) give it every hardware thread unless
// --threads says otherwise (the layout is the same for any count); batch and model run faces side
// by side instead, one thread each.
void use_all_threads_unless_given(const ParsedArgs& args, wefm_options& options);

}  // namespace wefm_cli
