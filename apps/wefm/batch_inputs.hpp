#pragma once
// Which faces `wefm batch` flattens, found from a directory or a list file.
#include <string>
#include <vector>

namespace wefm_cli {

struct BatchItem {
  std::string name;      // output base name (unique within the batch)
  std::string input;     // mesh file
  std::string seams;     // seam file to use ("" = none)
  std::string topology;  // topology file to use ("" = none)
};

// DIR: every mesh file in it (.obj .off .stl .ply), with a sibling <stem>.seam when it has data, and
// every sub-folder holding face.obj (the layout of data/real: face.seam, topo.json beside it).
// LISTFILE: one mesh file or face folder per line ('#' comments); relative paths are tried against
// the current directory first, then the list file's directory.
// `use_topology`: a face folder's topo.json replaces its face.seam.
// Returns false with a message when the path is unreadable or names nothing to flatten.
bool find_batch_items(const std::string& path, bool use_topology, std::vector<BatchItem>& items, std::string& error);

}  // namespace wefm_cli
