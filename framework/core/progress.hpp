#pragma once
// Progress reporting for long jobs: a redrawn bar on a terminal (stderr is a TTY), plain log lines
// otherwise (CI, pipes), at most one line every few seconds plus start and finish, each with the time left.
// A job still running after a couple of seconds prints, once, its estimated total time and the resident
// memory (issue 33: options with huge accepted maxima ran for hours without an estimate). Commands whose
// options allow hours of work also print, before any work, an estimate from their cost model
// (announce_estimate; the models are in experiments/cli/command_estimates.hpp).
#include <chrono>
#include <cstddef>
#include <functional>
#include <mutex>
#include <string>

namespace crowdlab {

/// What a Progress reports after each advance() or grow() (Progress::set_observer; tests).
struct ProgressUpdate {
  std::size_t units = 0;  ///< units this advance() passed (0 for grow())
  std::size_t done = 0;   ///< units done so far (at most total)
  std::size_t total = 0;  ///< units of the whole job as known now
};

class Progress {
 public:
  /// label: what is being done ("rendering c012/V3"); total: number of work units (> 0).
  Progress(std::string label, std::size_t total);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  /// Adds `units` completed work units. Thread-safe.
  void advance(std::size_t units = 1);
  /// Adds `units` work units to the total, for work found only once the job is under way (correct_crowd's
  /// extra lap, issue 28): prints "LABEL: WHY: +UNITS steps, now DONE/TOTAL (P%), T left", so the share
  /// done drops with a reason instead of the job stalling at 100 %. Thread-safe.
  void grow(std::size_t units, const std::string& why);
  /// Called (under the progress's lock, from the advancing thread) after every advance() and grow(), even
  /// when progress output is off: tests check what a job reports.
  void set_observer(std::function<void(const ProgressUpdate&)> observer);
  /// Marks the job finished (called by the destructor if not called explicitly).
  void finish();

  /// Globally silences progress output (tests, --quiet).
  static void set_enabled(bool enabled);
  /// After how many seconds of work a job's total time (from its rate so far) and the process's resident
  /// memory are printed, once (default 2 s; tests set 0).
  static void set_estimate_after(double seconds);

  /// Prints, once and before any work, a job's estimated total time and memory from a cost model:
  /// "[crowdlab] LABEL: estimated before starting: about T and M MB of memory for N UNITS". `extra_mb` is
  /// the memory the job will add to what the process holds now (which is added in). Silent when
  /// progress output is off (--quiet).
  static void announce_estimate(const std::string& label, double units, const std::string& unit_name,
                                double seconds, double extra_mb);

 private:
  void draw(bool final_line);
  /// Time left from the rate so far ("" before any unit is done).
  std::string time_left(double elapsed_s) const;
  std::string label_;
  std::size_t total_;
  std::size_t done_ = 0;
  bool finished_ = false;
  bool estimated_ = false;
  bool tty_;
  std::chrono::steady_clock::time_point start_, last_draw_;
  std::function<void(const ProgressUpdate&)> observer_;
  std::mutex mutex_;
};

}  // namespace crowdlab
