#pragma once
// The one way the commands that work face by face (batch, model, mesh-model) spread the faces over
// threads: each thread takes the next face until none is left or a stop is asked (stop.hpp), so a
// Ctrl-C leaves the faces not yet taken unstarted; progress is reported under one lock, so lines
// print whole and the count of finished faces rises by one per line.
#include <cstddef>
#include <functional>

namespace wefm_cli {

// Calls work(i) for i in [0, count) on up to `threads` threads (at least one). Where work returns
// true, finished(i, n) follows under the lock, n the number of faces finished so far (1, 2, ...);
// false is a face with nothing to do, not counted. Returns when every thread has ended.
void for_each_face(size_t count, size_t threads, const std::function<bool(size_t)>& work,
                   const std::function<void(size_t, size_t)>& finished);

}  // namespace wefm_cli
