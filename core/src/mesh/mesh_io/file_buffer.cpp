#include "file_buffer.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "wefm/core/sys/error.hpp"
#include "wefm/core/sys/huge_pages.hpp"

namespace wefm::io {

namespace {

struct Fd {
  int fd;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

FileBuffer::FileBuffer(const std::string& path) {
  Fd f{::open(path.c_str(), O_RDONLY | O_CLOEXEC)};
  if (f.fd < 0) fail(Errc::io, "cannot open '" + path + "' for reading: " + std::strerror(errno));
  struct stat st {};
  if (::fstat(f.fd, &st) != 0) fail(Errc::io, "cannot read '" + path + "': " + std::strerror(errno));
  if (S_ISDIR(st.st_mode)) fail(Errc::io, "cannot read '" + path + "': it is a directory");
  // Regular files: one allocation of the right size. Pipes and devices report no size: grow.
  std::size_t capacity = S_ISREG(st.st_mode) ? static_cast<std::size_t>(st.st_size) + 1 : std::size_t{1} << 20;
  data_.reset(new char[capacity]);
  advise_huge_pages(data_.get(), capacity);  // a 1M-triangle OBJ is 51 MB: 12k page faults in 4 KB pages
  while (true) {
    if (size_ + 1 >= capacity) {
      if (S_ISREG(st.st_mode) && size_ + 1 == capacity) {
        // The file may have grown since fstat; check with a one-byte probe before growing.
        char probe;
        const ssize_t n = ::read(f.fd, &probe, 1);
        if (n == 0) break;
        if (n < 0) {
          if (errno == EINTR) continue;
          fail(Errc::io, "error reading '" + path + "': " + std::strerror(errno));
        }
        data_[size_++] = probe;
      }
      std::unique_ptr<char[]> bigger(new char[2 * capacity]);
      std::memcpy(bigger.get(), data_.get(), size_);
      data_ = std::move(bigger);
      capacity *= 2;
    }
    const ssize_t n = ::read(f.fd, data_.get() + size_, capacity - 1 - size_);
    if (n == 0) break;
    if (n < 0) {
      if (errno == EINTR) continue;
      fail(Errc::io, "error reading '" + path + "': " + std::strerror(errno));
    }
    size_ += static_cast<std::size_t>(n);
  }
  data_[size_] = '\n';
}

}  // namespace wefm::io
