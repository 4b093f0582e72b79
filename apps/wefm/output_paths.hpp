#pragma once
#include <string>

namespace wefm_cli {

// Creates the parent directories of an output file so "-o out/x.obj" works in a fresh checkout.
// Returns false with a message naming the directory.
bool make_parent_dirs(const std::string& file, std::string& error);
bool make_dirs(const std::string& dir, std::string& error);

}  // namespace wefm_cli
