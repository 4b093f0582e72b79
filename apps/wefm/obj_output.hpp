#pragma once
#include <string>

#include "face_snapshot.hpp"

namespace wefm_cli {

// OBJ with `v` (3D, input order, so vertex indices match the input), `vt` (one per vertex use) and
// `f v/vt`. Returns 0 or 3 with a message. Written here rather than with wefm_face_write_obj so the
// header comment and number format are under the tool's control and it runs from the snapshot.
int write_uv_obj(const std::string& path, const std::string& input, const FaceSnapshot& snap, std::string& error);

}  // namespace wefm_cli
