// AtomicFile (core/include/wefm/core/sys/atomic_file.hpp), behind wefm_face_write_obj and
// wefm_domain_mesh_write_obj: a file is replaced whole or not at all.
#include <doctest/doctest.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <string>

#include "wefm/core/sys/atomic_file.hpp"
#include "wefm/core/sys/error.hpp"

namespace fs = std::filesystem;

namespace {

struct TempDir {
  fs::path path;
  TempDir() {
    std::string tmpl = (fs::temp_directory_path() / "wefm_atomic_XXXXXX").string();  // mkdtemp's template
    REQUIRE(mkdtemp(tmpl.data()) != nullptr);
    path = tmpl;
  }
  ~TempDir() { fs::remove_all(path); }
  size_t entries() const { return static_cast<size_t>(std::distance(fs::directory_iterator(path), fs::directory_iterator())); }
};

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void spit(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

// The error a write raised; none when the file was written.
std::optional<wefm::Errc> code_of(const std::string& path, const std::string& text) {
  try {
    wefm::AtomicFile f(path);
    f.write(text.data(), text.size());
    f.commit();
  } catch (const wefm::Error& e) {
    CHECK(std::string(e.what()).find(path) != std::string::npos);
    return e.code();
  }
  return std::nullopt;
}

}  // namespace

TEST_CASE("AtomicFile replaces a file whole and leaves no temporary") {
  TempDir d;
  const fs::path target = d.path / "out.obj";
  spit(target, "old");
  CHECK(code_of(target.string(), "new text") == std::nullopt);
  CHECK(slurp(target) == "new text");
  CHECK(d.entries() == 1);
}

TEST_CASE("AtomicFile: a failed write keeps the previous file (RLIMIT_FSIZE as a full disk)") {
  TempDir d;
  const fs::path target = d.path / "out.obj";
  spit(target, "old");
  struct rlimit old_limit;
  REQUIRE(getrlimit(RLIMIT_FSIZE, &old_limit) == 0);
  void (*old_handler)(int) = signal(SIGXFSZ, SIG_IGN);
  struct rlimit small = old_limit;
  small.rlim_cur = 64;
  REQUIRE(setrlimit(RLIMIT_FSIZE, &small) == 0);
  const std::optional<wefm::Errc> code = code_of(target.string(), std::string(4096, 'x'));
  setrlimit(RLIMIT_FSIZE, &old_limit);
  signal(SIGXFSZ, old_handler);
  CHECK(code == wefm::Errc::io);
  CHECK(slurp(target) == "old");
  CHECK(d.entries() == 1);
}

TEST_CASE("AtomicFile: /dev/full fails, /dev/null works, a folder or an empty name is refused") {
  if (fs::exists("/dev/full")) CHECK(code_of("/dev/full", "x") == wefm::Errc::io);
  CHECK(code_of("/dev/null", "x") == std::nullopt);
  TempDir d;
  CHECK(code_of(d.path.string(), "x") == wefm::Errc::io);
  CHECK(code_of((d.path / "missing" / "x.obj").string(), "x") == wefm::Errc::io);
  CHECK(code_of("", "x") == wefm::Errc::io);
}

TEST_CASE("AtomicFile follows a symbolic link: the file it names is replaced, the link stays") {
  TempDir d;
  spit(d.path / "real.obj", "old");
  fs::create_symlink(d.path / "real.obj", d.path / "link.obj");
  CHECK(code_of((d.path / "link.obj").string(), "new") == std::nullopt);
  CHECK(fs::is_symlink(d.path / "link.obj"));
  CHECK(slurp(d.path / "real.obj") == "new");
}

TEST_CASE("AtomicFile abandoned before commit leaves the previous file and no temporary") {
  TempDir d;
  const fs::path target = d.path / "out.obj";
  spit(target, "old");
  {
    wefm::AtomicFile f(target.string());
    f.write("partial", 7);
  }
  CHECK(slurp(target) == "old");
  CHECK(d.entries() == 1);
}

TEST_CASE("AtomicFile: a replaced file keeps its permission bits; a new file gets the umask's") {
  TempDir d;
  const fs::path target = d.path / "out.obj";
  spit(target, "old");
  fs::permissions(target, fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);  // 0640
  CHECK(code_of(target.string(), "new") == std::nullopt);
  CHECK(slurp(target) == "new");
  CHECK(fs::status(target).permissions() == (fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read));
  const mode_t old_mask = umask(022);
  const fs::path fresh = d.path / "fresh.obj";
  CHECK(code_of(fresh.string(), "x") == std::nullopt);
  umask(old_mask);
  CHECK(fs::status(fresh).permissions() == (fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read | fs::perms::others_read));
}
