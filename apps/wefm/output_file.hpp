#pragma once
// Every file the tool writes goes through OutputFile: common/replace_file (a temporary in the
// target's folder, checked writes, fsync, rename; special files such as /dev/null written in place;
// links followed; permissions kept), plus the tool's own policy. A stop request (Ctrl-C, SIGTERM, a
// time limit) fails the write and leaves the previous file; the temporary is on the signal-safe
// list of stop.hpp from before it exists, so a second Ctrl-C removes it from the signal handler.
// Only a SIGKILL can leave a temporary behind, never a partial target.
#include <cstddef>
#include <string>
#include <string_view>

#include "wefm/common/replace_file.hpp"

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
  bool fail();
  std::string path_;  // as given, for messages
  wefm_common::ReplaceFile file_;
  int slot_ = -1;
  bool stopped_ = false;
  std::string error_;
};

// One whole file from memory (reports, JSON, small text). Returns kExitOk, kExitIo, or the stop's
// exit code, with `error` set.
int write_file_atomically(const std::string& path, std::string_view text, std::string& error);

}  // namespace wefm_cli
