// libFuzzer target: the CLI's seam-file parser (apps/wefm/seams_file.cpp, `--seams` and face.seam).
// The bytes are the file. Properties: the status is 0, 3 or 4 and a failure names the file; a
// success gives whole pairs of indices in [0, 2^31); seams_file_has_data agrees with the parse
// (a file with data that parses has pairs, a file without data has none).
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "fuzz_input.hpp"
#include "seams_file.hpp"

using wefm_fuzz::violated;

namespace {

std::string input_path() {
  static const std::string path = [] {
    const char* t = std::getenv("TMPDIR");
    std::string tmpl = std::string(t && *t ? t : "/tmp") + "/wefm_fuzz_seams_XXXXXX";
    std::vector<char> buf(tmpl.begin(), tmpl.end());
    buf.push_back('\0');
    if (!mkdtemp(buf.data())) violated("mkdtemp", tmpl.c_str());
    static std::string dir(buf.data());
    std::atexit([] {
      std::remove((dir + "/face.seam").c_str());
      std::remove(dir.c_str());
    });
    return dir + "/face.seam";
  }();
  return path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = input_path();
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) violated("fopen", path.c_str());
  if (size && std::fwrite(data, 1, size, f) != size) violated("fwrite", path.c_str());
  std::fclose(f);
  std::vector<int32_t> pairs;
  std::string error;
  const int code = wefm_cli::read_seams_file(path, pairs, error);
  if (code != 0 && code != 3 && code != 4) violated("read_seams_file", "exit code outside 0, 3, 4");
  if (code != 0) {
    if (error.find(path) == std::string::npos) violated("read_seams_file", "a failure that does not name the file");
    return 0;
  }
  if (pairs.size() % 2 != 0) violated("read_seams_file", "an odd number of indices");
  for (int32_t v : pairs)
    if (v < 0) violated("read_seams_file", "a negative vertex index");
  if (wefm_cli::seams_file_has_data(path) != !pairs.empty()) violated("seams_file_has_data", "disagrees with the parse");
  return 0;
}
