#include "output_paths.hpp"

#include <filesystem>
#include <map>
#include <sys/stat.h>
#include <system_error>

namespace wefm_cli {

bool make_dirs(const std::string& dir, std::string& error) {
  if (dir.empty()) return true;
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec && !std::filesystem::is_directory(dir)) {
    error = dir + ": cannot create directory: " + ec.message();
    return false;
  }
  return true;
}

bool make_parent_dirs(const std::string& file, std::string& error) {
  return make_dirs(std::filesystem::path(file).parent_path().string(), error);
}

namespace {

// What identifies a file: "dev:ino" when it exists, else its canonical path. Special files: "".
std::string identity(const std::string& path) {
  struct stat st;
  if (stat(path.c_str(), &st) == 0) {
    if (!S_ISREG(st.st_mode)) return "";
    return "inode " + std::to_string(st.st_dev) + ":" + std::to_string(st.st_ino);
  }
  std::error_code ec;
  const std::filesystem::path p = std::filesystem::weakly_canonical(std::filesystem::absolute(path, ec), ec);
  return ec ? "path " + path : "path " + p.lexically_normal().string();
}

}  // namespace

bool check_output_paths(const std::vector<NamedPath>& inputs, const std::vector<NamedPath>& outputs, std::string& error) {
  std::map<std::string, const NamedPath*> seen;
  for (const NamedPath& in : inputs)
    if (!in.path.empty()) seen.emplace(identity(in.path), &in);
  for (const NamedPath& out : outputs) {
    if (out.path.empty()) {
      error = out.option + ": empty file name";
      return false;
    }
    const std::string id = identity(out.path);
    if (id.empty()) continue;
    const auto [it, fresh] = seen.emplace(id, &out);
    if (!fresh) {
      error = out.option + " " + out.path + " is the same file as " + it->second->option + " " + it->second->path +
              ": refusing to overwrite it";
      return false;
    }
  }
  return true;
}

}  // namespace wefm_cli
