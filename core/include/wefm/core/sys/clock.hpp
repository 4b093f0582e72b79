#pragma once
// The clock of the report's timers: seconds on the monotonic clock (differences only).
#include <chrono>

namespace wefm {

inline double now() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

}  // namespace wefm
