#include "wefm/core/mesh/obj_writer.hpp"

namespace wefm {

namespace {

// 4 MB blocks: a million-triangle file in a few dozen writes.
constexpr std::size_t kBlock = std::size_t{4} << 20;

}  // namespace

ObjWriter::ObjWriter(const std::string& path) : out_(kBlock, path), lines_(out_) {}

void ObjWriter::commit() {
  out_.flush();
  out_.sink().commit();
}

}  // namespace wefm
