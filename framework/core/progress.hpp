#pragma once
// Progress reporting for long jobs: a redrawn bar on a terminal (stderr is a TTY), plain log lines
// otherwise (CI, pipes), at most one line every few seconds plus start and finish.
#include <chrono>
#include <cstddef>
#include <mutex>
#include <string>

namespace crowdlab {

class Progress {
 public:
  /// label: what is being done ("rendering c012/V3"); total: number of work units (> 0).
  Progress(std::string label, std::size_t total);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  /// Adds `units` completed work units. Thread-safe.
  void advance(std::size_t units = 1);
  /// Marks the job finished (called by the destructor if not called explicitly).
  void finish();

  /// Globally silences progress output (tests, --quiet).
  static void set_enabled(bool enabled);

 private:
  void draw(bool final_line);
  std::string label_;
  std::size_t total_;
  std::size_t done_ = 0;
  bool finished_ = false;
  bool tty_;
  std::chrono::steady_clock::time_point start_, last_draw_;
  std::mutex mutex_;
};

}  // namespace crowdlab
