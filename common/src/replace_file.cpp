#include "wefm/common/replace_file.hpp"

#include <atomic>
#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace wefm_common {

namespace {

std::atomic<unsigned> g_counter{0};

std::string directory_of(const std::string& path) {
  const std::size_t slash = path.rfind('/');
  if (slash == std::string::npos) return ".";
  return slash == 0 ? "/" : path.substr(0, slash);
}

std::string file_name_of(const std::string& path) {
  const std::size_t slash = path.rfind('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

// The file that ends up replaced: a link to a regular file is followed, so the link survives.
std::string resolve_target(const std::string& path) {
  struct stat l;
  if (lstat(path.c_str(), &l) != 0 || !S_ISLNK(l.st_mode)) return path;
  char buf[PATH_MAX];
  if (!realpath(path.c_str(), buf)) return path;  // a dangling link: rename replaces the link itself
  return buf;
}

// The rename is durable once the folder's entry is on disk. Best effort: the file is already whole
// in place, and some file systems refuse fsync on a folder.
void sync_directory(const std::string& target) {
  const int fd = ::open(directory_of(target).c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  (void)fsync(fd);
  ::close(fd);
}

}  // namespace

bool ReplaceFile::fail(const std::string& what, int err) {
  if (!failed_) {
    failed_ = true;
    errno_ = err;
    error_ = what + (err ? std::string(": ") + std::strerror(err) : std::string());
  }
  return false;
}

bool ReplaceFile::prepare(const std::string& path) {
  discard();
  failed_ = direct_ = replaces_ = false;
  errno_ = 0;
  mode_ = 0;
  error_.clear();
  if (path.empty()) return fail("empty file name");
  target_ = resolve_target(path);
  struct stat st;
  if (stat(target_.c_str(), &st) == 0) {
    if (S_ISDIR(st.st_mode)) return fail("is a directory");
    direct_ = !S_ISREG(st.st_mode);
    replaces_ = true;
    mode_ = st.st_mode & 07777;
  }
  if (!direct_) {
    char suffix[64];
    std::snprintf(suffix, sizeof suffix, ".tmp-%ld-%u", static_cast<long>(getpid()), g_counter.fetch_add(1));
    temp_ = directory_of(target_) + "/." + file_name_of(target_) + suffix;
  }
  return true;
}

bool ReplaceFile::create() {
  if (failed_) return false;
  if (direct_) {
    fd_ = ::open(target_.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC | O_NOCTTY);
    return fd_ >= 0 || fail("cannot open for writing", errno);
  }
  fd_ = ::open(temp_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC | O_NOCTTY, 0666);
  if (fd_ < 0) {
    const int err = errno;
    temp_.clear();
    return fail("cannot create", err);
  }
  // A file that is replaced keeps its permissions (a read-only-for-others result stays so).
  if (replaces_ && fchmod(fd_, mode_) != 0) return fail("cannot set the permissions of the replacement", errno);
  return true;
}

bool ReplaceFile::write(const char* data, std::size_t size) {
  if (failed_) return false;
  if (fd_ < 0) return fail("not open", EBADF);
  while (size > 0) {
    const ssize_t n = ::write(fd_, data, size);
    if (n < 0) {
      if (errno == EINTR) continue;
      return fail("write failed", errno);
    }
    if (n == 0) return fail("write failed", EIO);
    data += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

bool ReplaceFile::commit() {
  if (!failed_ && fd_ < 0) fail("not open", EBADF);
  if (!failed_ && !direct_ && fsync(fd_) != 0) fail("write failed (fsync)", errno);
  if (fd_ >= 0) {
    const int rc = ::close(fd_);
    fd_ = -1;
    if (rc != 0 && !failed_) fail("write failed (close)", errno);
  }
  if (!failed_ && !direct_ && std::rename(temp_.c_str(), target_.c_str()) != 0) fail("cannot replace", errno);
  if (failed_) {
    discard();
    return false;
  }
  temp_.clear();
  if (!direct_) sync_directory(target_);
  return true;
}

void ReplaceFile::discard() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  if (!temp_.empty()) ::unlink(temp_.c_str());
  temp_.clear();
}

}  // namespace wefm_common
