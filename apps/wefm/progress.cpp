#include "progress.hpp"

#include <chrono>
#include <cstdio>
#include <unistd.h>

namespace wefm_cli {

CancelWatcher::CancelWatcher() : thread_([this] { loop(); }) {}

CancelWatcher::~CancelWatcher() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void CancelWatcher::add(wefm_face* face) {
  std::lock_guard<std::mutex> lock(mutex_);
  faces_.insert(face);
}

void CancelWatcher::remove(wefm_face* face) {
  std::lock_guard<std::mutex> lock(mutex_);
  faces_.erase(face);
}

void CancelWatcher::loop() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (!stop_) {
    // A signal cannot notify a condition variable, so poll: 50 ms is below what a user notices.
    wake_.wait_for(lock, std::chrono::milliseconds(50));
    // Removal takes the same mutex, so every face here is alive while we cancel it.
    if (interrupted())
      for (wefm_face* f : faces_) wefm_face_cancel(f);
  }
}

Progress::Progress(bool enabled, std::string prefix)
    : enabled_(enabled), tty_(isatty(fileno(stderr)) != 0), prefix_(std::move(prefix)) {}

int Progress::callback(void* self, double fraction, const char* stage) {
  return static_cast<Progress*>(self)->update(fraction, stage);
}

int Progress::update(double fraction, const char* stage) {
  if (interrupted()) return 1;
  if (!enabled_) return 0;
  const std::string name = stage ? stage : "";
  const int percent = fraction <= 0 ? 0 : fraction >= 1 ? 100 : static_cast<int>(fraction * 100.0);
  const bool new_stage = name != stage_;
  if (tty_) {
    if (!new_stage && percent == last_percent_) return 0;
    constexpr int kWidth = 30;
    char bar[kWidth + 1];
    const int filled = percent * kWidth / 100;
    for (int i = 0; i < kWidth; ++i) bar[i] = i < filled ? '#' : '-';
    bar[kWidth] = '\0';
    std::fprintf(stderr, "\r%s%-14s [%s] %3d%%", prefix_.c_str(), name.c_str(), bar, percent);
    std::fflush(stderr);
    bar_drawn_ = true;
  } else {
    // Logs and pipes: one line per stage change or 10 points of progress, never a flood.
    if (!new_stage && percent < last_percent_ + 10) return 0;
    std::fprintf(stderr, "%sprogress: %s %d%%\n", prefix_.c_str(), name.c_str(), percent);
  }
  stage_ = name;
  last_percent_ = percent;
  return 0;
}

void Progress::finish() {
  if (bar_drawn_) {
    std::fputs("\r\033[K", stderr);  // erase the bar line
    std::fflush(stderr);
    bar_drawn_ = false;
  }
}

}  // namespace wefm_cli
