#pragma once
// Progress display and stop requests for solves.
//
// Stopping (stop.hpp: Ctrl-C, SIGTERM, --time-limit) uses both routes the library offers: the
// progress callback returns non-zero once a stop was requested, and a watcher thread calls
// wefm_face_cancel() on every running face, so a stage that reports progress rarely (a long
// factorisation, the domain meshing) still stops at the library's next check.
#include <atomic>
#include <condition_variable>
#include <mutex>
#include <set>
#include <string>
#include <thread>

#include "stop.hpp"
#include "wefm/wefm.h"

namespace wefm_cli {

class CancelWatcher {
 public:
  CancelWatcher();
  ~CancelWatcher();
  CancelWatcher(const CancelWatcher&) = delete;
  CancelWatcher& operator=(const CancelWatcher&) = delete;
  void add(wefm_face* face);
  void remove(wefm_face* face);

 private:
  void loop();
  std::mutex mutex_;
  std::condition_variable wake_;
  std::set<wefm_face*> faces_;
  bool stop_ = false;
  std::thread thread_;
};

// Registers a face with the watcher for the lifetime of a solve.
class WatchedFace {
 public:
  WatchedFace(CancelWatcher* w, wefm_face* f) : watcher_(w), face_(f) {
    if (watcher_) watcher_->add(face_);
  }
  ~WatchedFace() {
    if (watcher_) watcher_->remove(face_);
  }
  WatchedFace(const WatchedFace&) = delete;
  WatchedFace& operator=(const WatchedFace&) = delete;

 private:
  CancelWatcher* watcher_;
  wefm_face* face_;
};

// One face's progress display: a redrawn bar on a terminal, sparse "progress:" lines otherwise.
class Progress {
 public:
  // `enabled` false: only the cancel check. `prefix` labels lines (batch uses the face name).
  Progress(bool enabled, std::string prefix);
  static int callback(void* self, double fraction, const char* stage);
  void finish();  // clears the bar so the summary starts on a clean line

 private:
  int update(double fraction, const char* stage);
  bool enabled_;
  bool tty_;
  std::string prefix_;
  std::string stage_;
  int last_percent_ = -100;
  bool bar_drawn_ = false;
};

}  // namespace wefm_cli
