#include "output_file.hpp"

#include "exit_codes.hpp"
#include "stop.hpp"

namespace wefm_cli {

bool OutputFile::fail() {
  if (error_.empty()) error_ = path_ + ": " + file_.error();
  return false;
}

bool OutputFile::open(const std::string& path) {
  discard();
  path_ = path;
  stopped_ = false;
  error_.clear();
  if (!file_.prepare(path)) return fail();
  // Registered before it exists, so that no moment leaves it unregistered.
  if (!file_.temporary().empty()) slot_ = register_temporary(file_.temporary());
  if (file_.create()) return true;
  unregister_temporary(slot_);
  slot_ = -1;
  return fail();
}

bool OutputFile::write(const char* data, size_t size) {
  if (file_.failed()) return false;
  if (interrupted()) {
    stopped_ = true;
    file_.fail("not written: " + stop_reason());
    return fail();
  }
  return file_.write(data, size) || fail();
}

bool OutputFile::commit() {
  if (!file_.failed() && interrupted()) {
    stopped_ = true;
    file_.fail("not written: " + stop_reason());
  }
  const bool ok = file_.commit();
  unregister_temporary(slot_);
  slot_ = -1;
  return ok || fail();
}

void OutputFile::discard() {
  file_.discard();
  unregister_temporary(slot_);
  slot_ = -1;
}

int write_file_atomically(const std::string& path, std::string_view text, std::string& error) {
  OutputFile out;
  if (out.open(path) && out.write(text.data(), text.size()) && out.commit()) return kExitOk;
  error = out.error();
  return out.stopped() ? stop_exit_code() : kExitIo;
}

}  // namespace wefm_cli
