#pragma once
// Targets that read their input from a file (the CLI's side files, CAD models): one private folder
// per process, removed at exit with what was written into it.
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <set>
#include <string>
#include <vector>

#include "fuzz_input.hpp"

namespace wefm_fuzz {

// Never destroyed: the atexit cleanup runs after static destructors registered later.
inline std::set<std::string>& written_files() {
  static auto* files = new std::set<std::string>;
  return *files;
}

inline const std::string& temp_folder() {
  static const std::string& dir = *new std::string([] {
    const char* t = std::getenv("TMPDIR");
    std::string tmpl = std::string(t && *t ? t : "/tmp") + "/wefm_fuzz_XXXXXX";
    std::vector<char> buf(tmpl.begin(), tmpl.end());
    buf.push_back('\0');
    if (!mkdtemp(buf.data())) violated("mkdtemp", tmpl.c_str());
    std::atexit([] {
      for (const std::string& f : written_files()) std::remove(f.c_str());
      std::remove(temp_folder().c_str());
    });
    return std::string(buf.data());
  }());
  return dir;
}

// A path in the folder, removed at exit.
inline std::string temp_path(const std::string& name) {
  const std::string path = temp_folder() + "/" + name;
  written_files().insert(path);
  return path;
}

// Writes the bytes to temp_path(name) and returns the path.
inline std::string write_temp_file(const std::string& name, const uint8_t* data, size_t size) {
  const std::string path = temp_path(name);
  FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) violated("fopen", path.c_str());
  if (size && std::fwrite(data, 1, size, f) != size) violated("fwrite", path.c_str());
  if (std::fclose(f) != 0) violated("fclose", path.c_str());
  return path;
}

// The CLI's readers answer 0, 3 (unreadable) or 4 (malformed) and name the file in a failure.
// True when the file was read.
inline bool cli_read_ok(int code, const std::string& error, const std::string& path, const char* reader) {
  if (code != 0 && code != 3 && code != 4) violated(reader, "exit code outside 0, 3, 4");
  if (code != 0 && error.find(path) == std::string::npos) violated(reader, "a failure that does not name the file");
  return code == 0;
}

}  // namespace wefm_fuzz
