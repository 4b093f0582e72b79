#include "output_paths.hpp"

#include <filesystem>
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

}  // namespace wefm_cli
