#pragma once
// What the opaque handles of wefm.h hold, and the guard every entry point runs its body in: no
// exception crosses the C boundary, every failure leaves a status and a message.
#include <atomic>
#include <cstring>
#include <new>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "wefm/core/sys/error.hpp"
#include "wefm/core/solve/face.hpp"
#include "wefm/core/mesh/mesh_io.hpp"
#include "wefm/wefm.h"

struct wefm_face {
  std::atomic<int> refs{1};
  wefm::Face face;
  std::string last_error;
  std::atomic<bool> cancel{false};
  wefm_progress_fn progress = nullptr;
  void* progress_user = nullptr;
  // Set while wefm_face_solve or wefm_face_mesh_domain runs: its progress callback may call back
  // into this face, which it may then only read (wefm.h, "Re-entrancy"); a release of the last
  // reference waits for the end.
  bool solving = false;
};

struct wefm_mesh {
  std::atomic<int> refs{1};
  wefm::TriMesh mesh;
  std::int64_t merged_vertices = 0;
};

namespace wefm::capi {

void set_thread_error(const std::string& message);

// A core error's message, with its remedy (wefm::Remedy) named in this API's calls and fields.
std::string api_message(const wefm::Error& e);

// The C status of a core error.
constexpr wefm_status status_of(wefm::Errc code) noexcept {
  switch (code) {
    case wefm::Errc::invalid_argument: return WEFM_ERROR_INVALID_ARGUMENT;
    case wefm::Errc::out_of_range: return WEFM_ERROR_OUT_OF_RANGE;
    case wefm::Errc::invalid_state: return WEFM_ERROR_INVALID_STATE;
    case wefm::Errc::invalid_mesh: return WEFM_ERROR_INVALID_MESH;
    case wefm::Errc::invalid_topology: return WEFM_ERROR_INVALID_TOPOLOGY;
    case wefm::Errc::invalid_constraint: return WEFM_ERROR_INVALID_CONSTRAINT;
    case wefm::Errc::singular: return WEFM_ERROR_SINGULAR;
    case wefm::Errc::not_positive_definite: return WEFM_ERROR_NOT_POSITIVE_DEFINITE;
    case wefm::Errc::not_converged: return WEFM_ERROR_NOT_CONVERGED;
    case wefm::Errc::cancelled: return WEFM_ERROR_CANCELLED;
    case wefm::Errc::out_of_memory: return WEFM_ERROR_OUT_OF_MEMORY;
    case wefm::Errc::io: return WEFM_ERROR_IO;
    case wefm::Errc::unsupported: return WEFM_ERROR_UNSUPPORTED;
    case wefm::Errc::internal: return WEFM_ERROR_INTERNAL;
  }
  return WEFM_ERROR_INTERNAL;
}

// A failure that only this API knows (a caller's buffer too short): its status as it is.
class ApiError : public std::runtime_error {
 public:
  ApiError(wefm_status status, const std::string& message) : std::runtime_error(message), status_(status) {}
  wefm_status status() const noexcept { return status_; }

 private:
  wefm_status status_;
};

// Runs `body`; maps exceptions to statuses and stores the message on `err` (or thread-locally).
template <class F>
wefm_status guarded(std::string* err, F&& body) noexcept {
  try {
    body();
    return WEFM_OK;
  } catch (const wefm::Error& e) {
    const std::string m = api_message(e);
    if (err) *err = m;
    set_thread_error(m);
    return status_of(e.code());
  } catch (const ApiError& e) {
    if (err) *err = e.what();
    set_thread_error(e.what());
    return e.status();
  } catch (const std::bad_alloc&) {
    const char* m = "out of memory";
    if (err) *err = m;
    set_thread_error(m);
    return WEFM_ERROR_OUT_OF_MEMORY;
  } catch (const std::system_error& e) {
    // A thread that cannot be started for want of memory (its stack under an address-space limit)
    // or of thread slots is resource exhaustion too, not a bug.
    const bool exhausted = e.code() == std::errc::not_enough_memory || e.code() == std::errc::resource_unavailable_try_again;
    const std::string m = std::string(exhausted ? "out of memory: " : "internal error: ") + e.what();
    if (err) *err = m;
    set_thread_error(m);
    return exhausted ? WEFM_ERROR_OUT_OF_MEMORY : WEFM_ERROR_INTERNAL;
  } catch (const std::exception& e) {
    const std::string m = std::string("internal error: ") + e.what();
    if (err) *err = m;
    set_thread_error(m);
    return WEFM_ERROR_INTERNAL;
  } catch (...) {
    if (err) *err = "internal error: unknown exception";
    set_thread_error("internal error: unknown exception");
    return WEFM_ERROR_INTERNAL;
  }
}

// What a call does to its face (wefm.h, "Re-entrancy").
enum class Access { read, change };

// A call that would change a face while it is solving (from inside its own progress callback):
// WEFM_ERROR_INVALID_STATE and a message naming `function`.
wefm_status refuse_while_solving(wefm_face* face, const char* function) noexcept;

// The guard of every call on a face handle: `body` under guarded(), unless it would change a face
// that is solving. The one place the re-entrancy rule is enforced.
template <class F>
wefm_status on_face(wefm_face* face, Access access, const char* function, F&& body) noexcept {
  if (access == Access::change && face->solving) return refuse_while_solving(face, function);
  return guarded(&face->last_error, std::forward<F>(body));
}

// The face's C progress callback as the core's (empty when it has none): a non-zero return asks to
// stop. A C++ caller could still throw through it: that is a stop too, never an unwinding through
// the solver's or the mesher's state.
inline wefm::ProgressFn progress_of(wefm_face* face) {
  if (!face->progress) return {};
  return [face](double f, const char* stage) {
    try {
      return face->progress(face->progress_user, f, stage) == 0;
    } catch (...) {
      return false;
    }
  };
}

// Marks a face busy for a solve or a meshing (the callback's re-entrancy rule), however it ends.
class BusyFace {
 public:
  explicit BusyFace(wefm_face* face) : face_(face) { face_->solving = true; }
  ~BusyFace() { face_->solving = false; }
  BusyFace(const BusyFace&) = delete;
  BusyFace& operator=(const BusyFace&) = delete;

 private:
  wefm_face* face_;
};

// After a solve or a meshing: the callback released the last reference, so the face outlived the
// call only to finish it and goes now.
inline void free_if_released(wefm_face* face) {
  if (!face->solving && face->refs.load() == 0) delete face;
}

// NULL handle: thread-local message, WEFM_ERROR_NULL_ARGUMENT.
wefm_status null_argument(const char* function, const char* argument);

// Size-query output (wefm.h "Buffers") of `items` records of `width` values, written straight into
// the caller's buffer by get(i, out) (a size query builds nothing; a 1M-triangle mesh's arrays were
// built twice in temporaries, once per call). Throws via the guard when the buffer is short.
template <class T, class Get>
void copy_out_records(std::size_t items, std::size_t width, T* buffer, std::int64_t capacity, std::int64_t* count, Get get) {
  if (!count) throw wefm::Error(wefm::Errc::invalid_argument, "count pointer is NULL");
  *count = static_cast<std::int64_t>(items * width);
  if (!buffer) return;
  if (capacity < *count)
    throw ApiError(WEFM_ERROR_BUFFER_TOO_SMALL, "buffer too small: capacity " + std::to_string(capacity) + " < " + std::to_string(*count) + " elements needed");
  for (std::size_t i = 0; i < items; ++i) get(i, buffer + i * width);
}

template <class T, class S>
void copy_out(const std::vector<S>& values, T* buffer, std::int64_t capacity, std::int64_t* count) {
  copy_out_records(values.size(), 1, buffer, capacity, count, [&](std::size_t i, T* out) { *out = static_cast<T>(values[i]); });
}

// Copy a versioned struct in or out: only the first struct_size bytes the caller knows about.
template <class T>
T read_versioned(const T* in, const T& defaults) {
  T out = defaults;
  const size_t n = in->struct_size < sizeof(T) ? in->struct_size : sizeof(T);
  std::memcpy(&out, in, n);
  out.struct_size = sizeof(T);
  return out;
}
template <class T>
void write_versioned(T* out, const T& value) {
  const size_t n = out->struct_size < sizeof(T) ? out->struct_size : sizeof(T);
  const size_t keep = out->struct_size;
  std::memcpy(out, &value, n);
  out->struct_size = keep;
}

void check_struct_size(size_t size, const char* name);
const char* thread_error();

}  // namespace wefm::capi

#define WEFM_REQUIRE(ptr, fn)                                  \
  do {                                                         \
    if (!(ptr)) return wefm::capi::null_argument(fn, #ptr);    \
  } while (0)
