#include "wefm/core/sys/parallel.hpp"

#include <algorithm>
#include <exception>
#include <thread>
#include <vector>

namespace wefm {

void parallel_for(int threads, Index n, const std::function<void(Index, Index)>& body, Index grain) {
  if (n <= 0) return;
  const Index parts = std::max<Index>(1, std::min<Index>(threads, n / std::max<Index>(1, grain)));
  if (parts <= 1) {
    body(0, n);
    return;
  }
  std::vector<std::exception_ptr> errors(static_cast<size_t>(parts));
  auto run = [&](Index p) {
    const Index begin = static_cast<Index>(static_cast<std::int64_t>(n) * p / parts);
    const Index end = static_cast<Index>(static_cast<std::int64_t>(n) * (p + 1) / parts);
    try {
      body(begin, end);
    } catch (...) {
      errors[static_cast<size_t>(p)] = std::current_exception();
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(static_cast<size_t>(parts - 1));
  try {
    for (Index p = 1; p < parts; ++p) pool.emplace_back(run, p);
  } catch (...) {  // could not start a thread: finish the missing ranges here
    for (Index p = static_cast<Index>(pool.size()) + 1; p < parts; ++p) run(p);
  }
  run(0);
  for (std::thread& t : pool) t.join();
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
}

}  // namespace wefm
