#include "wefm/core/sys/atomic_file.hpp"

#include <atomic>
#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "wefm/core/sys/error.hpp"

namespace wefm {

namespace {

std::atomic<unsigned> g_counter{0};

std::string resolve_link(const std::string& path) {
  struct stat l;
  char buf[PATH_MAX];
  if (lstat(path.c_str(), &l) != 0 || !S_ISLNK(l.st_mode) || !realpath(path.c_str(), buf)) return path;
  return buf;
}

std::string temporary_name(const std::string& target) {
  const std::size_t slash = target.rfind('/');
  const std::string dir = slash == std::string::npos ? "." : slash == 0 ? "/" : target.substr(0, slash);
  const std::string name = slash == std::string::npos ? target : target.substr(slash + 1);
  char suffix[64];
  std::snprintf(suffix, sizeof suffix, ".tmp-%ld-%u", static_cast<long>(getpid()), g_counter.fetch_add(1));
  return dir + "/." + name + suffix;
}

// The rename is durable once the folder's entry is on disk. Best effort: the file is already whole
// in place, and some file systems refuse fsync on a folder.
void sync_directory(const std::string& target) {
  const std::size_t slash = target.rfind('/');
  const std::string dir = slash == std::string::npos ? "." : slash == 0 ? "/" : target.substr(0, slash);
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  (void)fsync(fd);
  ::close(fd);
}

}  // namespace

AtomicFile::AtomicFile(const std::string& path) : path_(path), target_(resolve_link(path)) {
  if (path.empty()) fail("empty file name", 0);
  struct stat st;
  if (stat(target_.c_str(), &st) == 0) {
    if (S_ISDIR(st.st_mode)) fail("is a directory", 0);
    direct_ = !S_ISREG(st.st_mode);
    replaces_ = true;
    mode_ = st.st_mode & 07777;
  }
  if (direct_) {
    fd_ = ::open(target_.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC | O_NOCTTY);
  } else {
    temp_ = temporary_name(target_);
    fd_ = ::open(temp_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC | O_NOCTTY, 0666);
  }
  if (fd_ < 0) {
    temp_.clear();
    fail("cannot open for writing", errno);
  }
  // A file that is replaced keeps its permissions (a read-only-for-others result stays so).
  if (!direct_ && replaces_ && fchmod(fd_, mode_) != 0) fail("cannot set the permissions of the replacement", errno);
}

AtomicFile::~AtomicFile() {
  if (fd_ >= 0) ::close(fd_);
  if (!temp_.empty()) ::unlink(temp_.c_str());
}

void AtomicFile::fail(const std::string& what, int err) {
  throw Error(Errc::io, "'" + path_ + "': " + what + (err ? std::string(": ") + std::strerror(err) : std::string()));
}

void AtomicFile::write(const char* data, std::size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd_, data, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) fail("error writing", n < 0 ? errno : EIO);
    data += n;
    size -= static_cast<std::size_t>(n);
  }
}

void AtomicFile::commit() {
  if (!direct_ && fsync(fd_) != 0) fail("error writing (fsync)", errno);
  const int rc = ::close(fd_);
  fd_ = -1;
  if (rc != 0) fail("error writing (close)", errno);
  if (!direct_ && std::rename(temp_.c_str(), target_.c_str()) != 0) fail("cannot replace the file", errno);
  temp_.clear();
  if (!direct_) sync_directory(target_);
}

}  // namespace wefm
