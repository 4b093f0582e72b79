#include "seams_file.hpp"

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>

#include "exit_codes.hpp"

namespace wefm_cli {

namespace {

// Strips the comment and surrounding blanks; returns false for lines with nothing left.
bool content_of(std::string& line) {
  const size_t hash = line.find('#');
  if (hash != std::string::npos) line.resize(hash);
  const size_t first = line.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return false;
  line = line.substr(first, line.find_last_not_of(" \t\r\n") - first + 1);
  return true;
}

}  // namespace

int read_seams_file(const std::string& path, std::vector<int32_t>& pairs, std::string& error) {
  std::ifstream in(path);
  if (!in) {
    error = path + ": cannot open seam file: " + std::strerror(errno);
    return kExitIo;
  }
  std::string line;
  long line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (!content_of(line)) continue;
    const char* p = line.c_str();
    char* end = nullptr;
    long long v[2];
    bool ok = true;
    for (auto& x : v) {
      errno = 0;
      x = std::strtoll(p, &end, 10);
      if (end == p || errno != 0 || x < 0 || x > 2147483647LL) ok = false;
      p = end;
    }
    while (ok && (*p == ' ' || *p == '\t')) ++p;
    if (!ok || *p != '\0') {
      error = path + ":" + std::to_string(line_no) + ": expected two 0-based vertex indices, got '" + line + "'";
      return kExitInvalid;
    }
    pairs.push_back(static_cast<int32_t>(v[0]));
    pairs.push_back(static_cast<int32_t>(v[1]));
  }
  if (in.bad()) {
    error = path + ": read error";
    return kExitIo;
  }
  return kExitOk;
}

bool seams_file_has_data(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line))
    if (content_of(line)) return true;
  return false;
}

}  // namespace wefm_cli
