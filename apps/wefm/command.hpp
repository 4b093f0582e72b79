#pragma once
// A subcommand is one file defining a `Command` plus one line in commands.cpp: main() only dispatches.
#include <string>
#include <vector>

namespace wefm_cli {

struct Command {
  const char* name;
  const char* summary;                                 // one line for `wefm --help`
  int (*run)(const std::vector<std::string>& args);    // args after the command name; returns exit code
};

const std::vector<Command>& commands();

// Defined in cmd_*.cpp.
Command flatten_command();
Command info_command();
Command batch_command();
Command model_command();
Command mesh_command();
Command mesh_model_command();

}  // namespace wefm_cli
