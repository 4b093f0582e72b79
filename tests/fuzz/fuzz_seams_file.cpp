// libFuzzer target: the CLI's seam-file parser (apps/wefm/seams_file.cpp, `--seams` and face.seam).
// The bytes are the file. Properties: the status is 0, 3 or 4 and a failure names the file; a
// success gives whole pairs of indices in [0, 2^31); seams_file_has_data agrees with the parse
// (a file with data that parses has pairs, a file without data has none).
#include <string>
#include <vector>

#include "fuzz_files.hpp"
#include "seams_file.hpp"

using wefm_fuzz::violated;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = wefm_fuzz::write_temp_file("face.seam", data, size);
  std::vector<int32_t> pairs;
  std::string error;
  if (!wefm_fuzz::cli_read_ok(wefm_cli::read_seams_file(path, pairs, error), error, path, "read_seams_file")) return 0;
  if (pairs.size() % 2 != 0) violated("read_seams_file", "an odd number of indices");
  for (int32_t v : pairs)
    if (v < 0) violated("read_seams_file", "a negative vertex index");
  if (wefm_cli::seams_file_has_data(path) != !pairs.empty()) violated("seams_file_has_data", "disagrees with the parse");
  return 0;
}
