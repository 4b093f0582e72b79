#pragma once
// `wefm model --atlas`: one SVG with every face's UV domain in a grid cell, each fitted to its cell
// (domains of one model differ in size by orders of magnitude, so one common scale would hide the
// small faces). Colours as in the single-face picture (domain_picture.hpp): area distortion on a
// diverging map, flips black with a magenta outline, loops black, seams green. Faces without a
// result get a grey cell with their failure reason.
#include <string>
#include <vector>

#include "face_snapshot.hpp"

namespace wefm_cli {

struct AtlasCell {
  std::string title;            // e.g. "f12 cylinder"
  std::string caption;          // e.g. "score 0.98" or the failure reason
  const FaceSnapshot* snap = nullptr;  // nullptr or no result: failed face
};

// Returns 0 or 3 (cannot write) with a message.
int write_model_atlas(const std::string& path, const std::string& title, const std::vector<AtlasCell>& cells,
                      std::string& error);

}  // namespace wefm_cli
