#pragma once
// A whole file in memory with a '\n' sentinel after the last byte, so line and token scanners can
// stop on the sentinel instead of testing the end on every character. One read() of the file's
// size: the file comes in with one copy and no re-allocation, whatever its size.
#include <cstddef>
#include <memory>
#include <string>

namespace wefm::io {

class FileBuffer {
 public:
  // Throws Error(io) naming the path and the system's reason.
  explicit FileBuffer(const std::string& path);
  const char* begin() const { return data_.get(); }
  const char* end() const { return data_.get() + size_; }  // *end() == '\n'
  std::size_t size() const { return size_; }

 private:
  std::unique_ptr<char[]> data_;
  std::size_t size_ = 0;
};

}  // namespace wefm::io
