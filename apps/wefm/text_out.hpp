#pragma once
// The tool's buffered text file, for every large output (OBJ, MSH, VTK, VTU, PLY, SVG of a million
// triangles): common/text_buffer (one block, std::to_chars numbers: put, num, general, fixed,
// integer, real) writing through OutputFile (output_file.hpp), so the target is replaced whole on
// close, or not at all, and a stop request fails the file at its next block.
#include <cstddef>
#include <string>

#include "exit_codes.hpp"
#include "output_file.hpp"
#include "stop.hpp"
#include "wefm/common/text_buffer.hpp"

namespace wefm_cli {

class TextOut : public wefm_common::TextBuffer<OutputFile> {
 public:
  // 1 MB blocks: each block is a write, and each write a check for a stop request.
  TextOut() : TextBuffer(std::size_t{1} << 20) {}

  // False with error() when the file cannot be created.
  bool open(const std::string& path) { return sink().open(path); }
  // Flushes and puts the file in place; false with error() if anything failed (a full disk shows up
  // here at the latest) or a stop was requested, and then the previous file is left as it was.
  bool close() {
    flush();
    return sink().commit();
  }
  const std::string& error() const { return sink().error(); }
  // Exit code for a failed close: an I/O error, or the stop's own code (stop.hpp).
  int failure_code() const { return sink().stopped() ? stop_exit_code() : kExitIo; }
};

}  // namespace wefm_cli
