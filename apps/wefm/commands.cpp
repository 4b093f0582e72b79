#include "command.hpp"

namespace wefm_cli {

const std::vector<Command>& commands() {
  // Registration: one line per subcommand, in the order `wefm --help` lists them.
  static const std::vector<Command> table = {
      flatten_command(),
      info_command(),
      batch_command(),
      model_command(),
      mesh_command(),
      mesh_model_command(),
  };
  return table;
}

}  // namespace wefm_cli
