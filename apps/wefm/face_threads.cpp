#include "face_threads.hpp"

#include <algorithm>
#include <atomic>
#include <mutex>
#include <thread>
#include <vector>

#include "stop.hpp"

namespace wefm_cli {

void for_each_face(size_t count, size_t threads, const std::function<bool(size_t)>& work,
                   const std::function<void(size_t, size_t)>& finished) {
  std::atomic<size_t> next{0};
  size_t done = 0;  // under `lock`
  std::mutex lock;
  auto worker = [&] {
    for (size_t i; !interrupted() && (i = next++) < count;) {
      if (!work(i)) continue;
      std::lock_guard<std::mutex> hold(lock);
      finished(i, ++done);
    }
  };
  std::vector<std::thread> pool;
  const size_t n = std::max<size_t>(1, std::min(threads, count));
  for (size_t t = 0; t < n; ++t) pool.emplace_back(worker);
  for (auto& t : pool) t.join();
}

}  // namespace wefm_cli
