#pragma once
// The library's files (wefm_face_write_obj, wefm_domain_mesh_write_obj) are replaced whole or not at
// all: common/replace_file (temporary in the target's folder, checked writes, fsync, rename; a
// special file such as /dev/null written in place; links followed; permissions kept), with each
// failure raised as Error(io) naming the file.
#include <cstddef>
#include <string>

#include "wefm/common/replace_file.hpp"

namespace wefm {

class AtomicFile {
 public:
  // Throws Error(io) naming the file when it cannot be created.
  explicit AtomicFile(const std::string& path);
  ~AtomicFile() = default;  // removes the temporary unless commit() succeeded
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  void write(const char* data, std::size_t size);  // throws Error(io)
  void commit();                                   // fsync, close, rename; throws Error(io)

 private:
  [[noreturn]] void fail();
  std::string path_;
  wefm_common::ReplaceFile file_;
};

}  // namespace wefm
