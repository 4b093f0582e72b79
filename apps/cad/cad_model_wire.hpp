#pragma once
// A CadModel as bytes: the CAD import runs in a child process (Open CASCADE cannot be interrupted,
// so the tool kills the child at the time limit) and hands the model back through a pipe. Both
// ends are the same build, so the layout is plain native integers and doubles; the decoder still
// checks every size against the bytes left, so a truncated or garbled stream is refused, not read
// out of bounds.
#include <string>
#include <string_view>

#include "cad_model.hpp"

namespace wefm_cad {

std::string encode_cad_model(const CadModel& model);
// False when the bytes are not one whole encoded model.
bool decode_cad_model(std::string_view bytes, CadModel& model);

}  // namespace wefm_cad
