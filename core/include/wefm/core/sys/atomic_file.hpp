#pragma once
// The library's files (wefm_face_write_obj, wefm_domain_mesh_write_obj) are replaced whole or not at
// all: the bytes go to a temporary file in the target's folder (unique name, O_EXCL), every write,
// the fsync and the close are checked, and rename() puts it in place. On any failure the temporary
// is removed and the previous file stays as it was. A target that exists and is not a regular file
// (/dev/null, /dev/full, a FIFO) cannot be replaced: it is written in place, every write and the
// close still checked. A symbolic link to a regular file is followed (the link stays). A replaced
// file keeps its permission bits; the folder is synced after the rename.
#include <cstddef>
#include <string>

namespace wefm {

class AtomicFile {
 public:
  // Throws Error(io) naming the file when it cannot be created.
  explicit AtomicFile(const std::string& path);
  ~AtomicFile();  // removes the temporary unless commit() succeeded
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  void write(const char* data, std::size_t size);  // throws Error(io)
  void commit();                                   // fsync, close, rename; throws Error(io)

 private:
  [[noreturn]] void fail(const std::string& what, int err);
  std::string path_, target_, temp_;
  int fd_ = -1;
  bool direct_ = false;
  bool replaces_ = false;  // the target exists: its permissions carry over
  unsigned mode_ = 0;
};

}  // namespace wefm
