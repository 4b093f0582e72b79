#include "batch_inputs.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <set>

#include "seams_file.hpp"

namespace wefm_cli {

namespace fs = std::filesystem;

namespace {

bool is_mesh_file(const fs::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".obj" || ext == ".off" || ext == ".stl" || ext == ".ply";
}

// "faces/a/", "faces/a/." and "." name the folder by its own name, never "" (the outputs would be
// the hidden files ".obj" and ".json").
std::string folder_name(const fs::path& dir) {
  std::error_code ec;
  fs::path p = fs::weakly_canonical(fs::absolute(dir, ec), ec);
  if (ec) p = dir.lexically_normal();
  while (!p.empty() && !p.has_filename() && p.has_relative_path()) p = p.parent_path();
  const std::string name = p.filename().string();
  return name.empty() || name == "." || name == ".." ? std::string("face") : name;
}

bool is_face_folder(const fs::path& dir) {
  std::error_code ec;
  return fs::is_regular_file(dir / "face.obj", ec);
}

class Collector {
 public:
  Collector(bool use_topology, std::vector<BatchItem>& items) : use_topology_(use_topology), items_(items) {}

  void add_folder(const fs::path& dir) {
    BatchItem item;
    item.input = (dir / "face.obj").string();
    std::error_code ec;
    const fs::path topo = dir / "topo.json", seam = dir / "face.seam";
    if (use_topology_ && fs::is_regular_file(topo, ec)) item.topology = topo.string();
    else if (fs::is_regular_file(seam, ec) && seams_file_has_data(seam.string())) item.seams = seam.string();
    add(folder_name(dir), std::move(item));
  }

  void add_file(const fs::path& file) {
    if (file.filename() == "face.obj") return add_folder(file.parent_path().empty() ? fs::path(".") : file.parent_path());
    BatchItem item;
    item.input = file.string();
    fs::path seam = file;
    seam.replace_extension(".seam");
    std::error_code ec;
    if (fs::is_regular_file(seam, ec) && seams_file_has_data(seam.string())) item.seams = seam.string();
    const std::string stem = file.stem().string();
    add(stem.empty() ? std::string("face") : stem, std::move(item));
  }

 private:
  // Same stem twice (a.obj and a.stl) must not overwrite each other's outputs.
  void add(std::string name, BatchItem item) {
    std::string unique = name;
    for (int k = 2; !names_.insert(unique).second; ++k) unique = name + "_" + std::to_string(k);
    item.name = unique;
    items_.push_back(std::move(item));
  }

  bool use_topology_;
  std::vector<BatchItem>& items_;
  std::set<std::string> names_;
};

}  // namespace

bool find_batch_items(const std::string& path, bool use_topology, std::vector<BatchItem>& items, std::string& error) {
  Collector collect(use_topology, items);
  std::error_code ec;
  const fs::path root(path);
  if (fs::is_directory(root, ec)) {
    if (is_face_folder(root)) {
      collect.add_folder(root);
      return true;
    }
    std::vector<fs::path> entries;
    for (fs::directory_iterator it(root, ec), end; !ec && it != end; it.increment(ec)) entries.push_back(it->path());
    if (ec) {
      error = path + ": cannot list directory: " + ec.message();
      return false;
    }
    std::sort(entries.begin(), entries.end());  // stable output order whatever the file system says
    for (const auto& p : entries) {
      if (fs::is_directory(p, ec) && is_face_folder(p)) collect.add_folder(p);
      else if (fs::is_regular_file(p, ec) && is_mesh_file(p)) collect.add_file(p);
    }
    if (items.empty()) error = path + ": no mesh files (.obj .off .stl .ply) or face folders (face.obj) in it";
    return !items.empty();
  }
  std::ifstream in(path);
  if (!in) {
    error = path + ": cannot open (expected a directory or a list file)";
    return false;
  }
  std::string line;
  long line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    const size_t hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    const size_t a = line.find_first_not_of(" \t\r"), b = line.find_last_not_of(" \t\r");
    if (a == std::string::npos) continue;
    fs::path p = line.substr(a, b - a + 1);
    if (p.is_relative() && !fs::exists(p, ec) && fs::exists(root.parent_path() / p, ec)) p = root.parent_path() / p;
    if (fs::is_directory(p, ec) && is_face_folder(p)) collect.add_folder(p);
    else collect.add_file(p);  // a missing file fails later as that face's own error, not the batch's
  }
  if (items.empty()) error = path + ": the list names no files";
  return !items.empty();
}

}  // namespace wefm_cli
