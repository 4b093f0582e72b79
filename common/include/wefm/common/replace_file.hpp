#pragma once
// A file replaced whole or not at all, for the library and the tool alike: the bytes go to a
// temporary file in the target's folder (unique name, O_EXCL); every write, the fsync and the close
// are checked, and rename() then puts the file in place. A failed or abandoned write removes the
// temporary and leaves the previous file as it was.
//
// A target that exists and is not a regular file (/dev/null, /dev/full, a FIFO) cannot be replaced
// by rename: it is written in place, still checking every write and the close, so /dev/full fails.
// A symbolic link to a regular file is followed: the file it names is replaced, the link stays.
// A replaced file keeps its permission bits; the folder is synced after the rename.
//
// Plain POSIX and the standard library: the library wraps it in exceptions (wefm::AtomicFile), the
// tool in its stop requests and its signal-safe list of temporaries (wefm_cli::OutputFile).
#include <cstddef>
#include <string>

namespace wefm_common {

class ReplaceFile {
 public:
  ReplaceFile() = default;
  ~ReplaceFile() { discard(); }
  ReplaceFile(const ReplaceFile&) = delete;
  ReplaceFile& operator=(const ReplaceFile&) = delete;

  // Resolves `path`, refuses an empty name or a folder, and names the temporary; creates nothing.
  bool prepare(const std::string& path);
  // The temporary's name, known after prepare() (empty when the target is written in place): a
  // caller that removes temporaries from a signal handler registers it before create().
  const std::string& temporary() const { return temp_; }
  // Opens the temporary (or the special file in place), with the replaced file's permissions.
  bool create();
  bool write(const char* data, std::size_t size);
  // fsync, close, rename over the target, sync the folder. False: the target is unchanged.
  bool commit();
  // Closes and removes the temporary; the target is untouched.
  void discard();

  // The first failure: what failed and why ("cannot create: Permission denied"), without the path.
  bool failed() const { return failed_; }
  const std::string& error() const { return error_; }
  int error_number() const { return errno_; }

  // Records a failure that is not the file's own (a stop request): write() and commit() then fail.
  bool fail(const std::string& what, int err = 0);

 private:
  std::string target_;  // what is replaced (symbolic links resolved)
  std::string temp_;
  int fd_ = -1;
  bool direct_ = false;
  bool replaces_ = false;  // the target exists: its permissions carry over
  unsigned mode_ = 0;
  bool failed_ = false;
  int errno_ = 0;
  std::string error_;
};

}  // namespace wefm_common
