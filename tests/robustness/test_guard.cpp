// The C API's one exception guard (capi/src/handles.hpp): every exception becomes a status and a
// message; exhaustion of memory or of threads is WEFM_ERROR_OUT_OF_MEMORY, never INTERNAL.
#include <doctest/doctest.h>

#include <new>
#include <stdexcept>
#include <string>
#include <system_error>

#include "handles.hpp"

using wefm::capi::guarded;

TEST_CASE("the guard maps exhausted memory and threads to OUT_OF_MEMORY and anything else unknown to INTERNAL") {
  std::string err;
  CHECK(guarded(&err, [] { throw std::bad_alloc(); }) == WEFM_ERROR_OUT_OF_MEMORY);
  CHECK(err == "out of memory");
  // std::thread and std::async under an address-space limit: EAGAIN ("Resource temporarily
  // unavailable", the message `ulimit -v 200M` used to give as an internal error), or ENOMEM.
  CHECK(guarded(&err, [] { throw std::system_error(std::make_error_code(std::errc::resource_unavailable_try_again)); }) == WEFM_ERROR_OUT_OF_MEMORY);
  CHECK(err.rfind("out of memory: ", 0) == 0);
  CHECK(std::string(wefm_last_error()) == err);
  CHECK(guarded(&err, [] { throw std::system_error(std::make_error_code(std::errc::not_enough_memory)); }) == WEFM_ERROR_OUT_OF_MEMORY);
  CHECK(guarded(&err, [] { throw std::system_error(std::make_error_code(std::errc::invalid_argument)); }) == WEFM_ERROR_INTERNAL);
  CHECK(err.rfind("internal error: ", 0) == 0);
  CHECK(guarded(&err, [] { throw std::runtime_error("x"); }) == WEFM_ERROR_INTERNAL);
  CHECK(guarded(&err, [] { throw wefm::Error(wefm::Errc::io, "cannot write"); }) == WEFM_ERROR_IO);
  CHECK(err == "cannot write");
  CHECK(guarded(nullptr, [] {}) == WEFM_OK);
}
