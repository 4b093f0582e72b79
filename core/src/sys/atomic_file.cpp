#include "wefm/core/sys/atomic_file.hpp"

#include "wefm/core/sys/error.hpp"

namespace wefm {

AtomicFile::AtomicFile(const std::string& path) : path_(path) {
  if (!file_.prepare(path) || !file_.create()) fail();
}

void AtomicFile::fail() { throw Error(Errc::io, "'" + path_ + "': " + file_.error()); }

void AtomicFile::write(const char* data, std::size_t size) {
  if (!file_.write(data, size)) fail();
}

void AtomicFile::commit() {
  if (!file_.commit()) fail();
}

}  // namespace wefm
