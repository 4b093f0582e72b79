#pragma once
// Every file the tool writes goes through OutputFile. The bytes go to a temporary file in the
// target's folder (unique name, O_EXCL); every write, the fsync and the close are checked, and
// rename() then puts the file in place. A failed, cancelled or timed-out write removes the
// temporary and leaves the previous file as it was; a second Ctrl-C removes it from the signal
// handler (stop.hpp). Only a SIGKILL can leave a temporary behind, never a partial target.
//
// A target that exists and is not a regular file (/dev/null, /dev/full, a FIFO) cannot be replaced
// by rename: it is written in place, still checking every write and the close, so /dev/full fails.
// A symbolic link to a regular file is followed: the file it names is replaced, the link stays.
// A replaced file keeps its permission bits; the folder is synced after the rename.
#include <cstddef>
#include <string>
#include <string_view>

namespace wefm_cli {

class OutputFile {
 public:
  OutputFile() = default;
  ~OutputFile() { discard(); }
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  // False with error() when the temporary (or the special file) cannot be opened.
  bool open(const std::string& path);
  // False once any write failed or a stop was requested (interrupted(), stop.hpp); sticky.
  bool write(const char* data, size_t size);
  // fsync, close, rename over the target. False with error(): the target is unchanged.
  bool commit();
  // Closes and removes the temporary (nothing happens to the target).
  void discard();
  // "PATH: what failed: why".
  const std::string& error() const { return error_; }
  // The failure was a stop request, not an I/O error (the caller's exit code is stop_exit_code()).
  bool stopped() const { return stopped_; }

 private:
  bool fail(const std::string& what, int err);
  std::string path_;    // as given, for messages
  std::string target_;  // what is replaced (symbolic links resolved)
  std::string temp_;
  int fd_ = -1;
  int slot_ = -1;
  bool direct_ = false;
  bool failed_ = false;
  bool stopped_ = false;
  std::string error_;
};

// One whole file from memory (reports, JSON, small text). Returns kExitOk, kExitIo, or the stop's
// exit code, with `error` set.
int write_file_atomically(const std::string& path, std::string_view text, std::string& error);

}  // namespace wefm_cli
