#pragma once
// Errors raised inside the core. The C API turns each into its status code and message; nothing
// else in the core reports failure, so every failure carries a precise, user-facing message.
#include <cstdio>
#include <stdexcept>
#include <string>

namespace wefm {

// What went wrong, in the core's terms. An API chooses its own codes for these (the C API's
// wefm_status: capi/src/handles.hpp, status_of), so the numbers here carry no meaning.
enum class Errc : int {
  invalid_argument,
  out_of_range,
  invalid_state,
  invalid_mesh,
  invalid_topology,
  invalid_constraint,
  singular,
  not_positive_definite,
  not_converged,
  cancelled,
  out_of_memory,
  io,
  unsupported,
  internal,
};

// What the caller can do about an error, where the message alone cannot name it: the core does not
// know the calls and fields of the API it is used through, so each API (the C API: capi/src/
// handles.hpp) names them in its own terms after the message.
enum class Remedy : int {
  none,
  set_mesh,        // give the face a mesh first
  solve_first,     // solve the face first
  add_seams,       // give seams that cut the surface open
  seams_or_cut,    // give seams, or turn on the automatic cut
};

class Error : public std::runtime_error {
 public:
  Error(Errc code, const std::string& message, Remedy remedy = Remedy::none) : std::runtime_error(message), code_(code), remedy_(remedy) {}
  Errc code() const noexcept { return code_; }
  Remedy remedy() const noexcept { return remedy_; }

 private:
  Errc code_;
  Remedy remedy_;
};

[[noreturn]] inline void fail(Errc code, const std::string& message, Remedy remedy = Remedy::none) { throw Error(code, message, remedy); }

// A number for a message, to 3 significant digits (1.7e+308, 0.125).
inline std::string message_number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

}  // namespace wefm
