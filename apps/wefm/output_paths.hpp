#pragma once
#include <string>
#include <vector>

namespace wefm_cli {

// Creates the parent directories of an output file so "-o out/x.obj" works in a fresh checkout.
// Returns false with a message naming the directory.
bool make_parent_dirs(const std::string& file, std::string& error);
bool make_dirs(const std::string& dir, std::string& error);

// One file the command reads or writes, named for messages by its option ("-o", "--report", "input").
struct NamedPath {
  std::string option;
  std::string path;
};

// Refuses, before any work (exit 2), an empty output name and outputs that are the same file as an
// input or as another output, however spelt: existing files are compared by device and inode (so a
// symbolic link or a hard link to the input counts), files still to be made by their canonical path.
// Special files (/dev/null) may repeat: they are not replaced. Inputs that are "" are skipped.
bool check_output_paths(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs, std::string& error);

}  // namespace wefm_cli
