#include "framework/core/progress.hpp"

#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <string>

namespace crowdlab {
namespace {
std::atomic<bool> g_enabled{true};

/// When a job has run this long, its total time is estimated from its rate so far and printed once: the
/// options with huge accepted maxima (power --simulations, simulate-study --observers, metrics --depth,
/// ...) ran for hours without a word (issue 33).
std::atomic<double> g_estimate_after_s{2.0};

/// Resident memory of this process in MB (Linux /proc/self/statm), 0 when unknown.
long resident_mb() {
  FILE* f = std::fopen("/proc/self/statm", "r");
  if (!f) return 0;
  long size = 0, resident = 0;
  const int got = std::fscanf(f, "%ld %ld", &size, &resident);
  std::fclose(f);
  return got == 2 ? resident * (sysconf(_SC_PAGESIZE) / 1024) / 1024 : 0;
}

/// "42 s", "17 min", "3.2 h", "4.1 days", "3.1e+07 years" (the models of options with huge maxima).
std::string duration_text(double s) {
  char buf[32];
  if (s < 120)
    std::snprintf(buf, sizeof buf, "%.0f s", s);
  else if (s < 7200)
    std::snprintf(buf, sizeof buf, "%.0f min", s / 60);
  else if (s < 172800)
    std::snprintf(buf, sizeof buf, "%.1f h", s / 3600);
  else if (s < 2 * 365.25 * 86400)
    std::snprintf(buf, sizeof buf, "%.1f days", s / 86400);
  else
    std::snprintf(buf, sizeof buf, "%.3g years", s / (365.25 * 86400));
  return buf;
}

}  // namespace

void Progress::set_enabled(bool enabled) {
  g_enabled = enabled;
}

void Progress::set_estimate_after(double seconds) {
  g_estimate_after_s = seconds;
}

void Progress::announce_estimate(const std::string& label, double units, const std::string& unit_name,
                                 double seconds, double extra_mb) {
  if (!g_enabled) return;
  std::fprintf(stderr,
               "[crowdlab] %s: estimated before starting: about %s and %.0f MB of memory for %.3g %s "
               "(progress lines below give the time left)\n",
               label.c_str(), duration_text(seconds).c_str(), static_cast<double>(resident_mb()) + extra_mb,
               units, unit_name.c_str());
  std::fflush(stderr);
}

Progress::Progress(std::string label, std::size_t total)
    : label_(std::move(label)), total_(total == 0 ? 1 : total), tty_(isatty(STDERR_FILENO) != 0) {
  start_ = last_draw_ = std::chrono::steady_clock::now();
  if (g_enabled && !tty_)
    std::fprintf(stderr, "[crowdlab] %s: started (%zu steps)\n", label_.c_str(), total_);
}

Progress::~Progress() {
  finish();
}

void Progress::set_observer(std::function<void(const ProgressUpdate&)> observer) {
  std::lock_guard lock(mutex_);
  observer_ = std::move(observer);
}

std::string Progress::time_left(double elapsed_s) const {
  const double frac = static_cast<double>(done_) / static_cast<double>(total_);
  return frac > 0 ? duration_text(elapsed_s * (1.0 - frac) / frac) + " left" : std::string();
}

void Progress::grow(std::size_t units, const std::string& why) {
  std::lock_guard lock(mutex_);
  total_ += units;
  if (observer_) observer_({0, done_, total_});
  if (!g_enabled || units == 0) return;
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const std::string left = time_left(elapsed);
  std::fprintf(stderr, "%s[crowdlab] %s: %s: +%zu steps, now %zu/%zu (%d%%)%s%s\n", tty_ ? "\r\033[K" : "",
               label_.c_str(), why.c_str(), units, done_, total_,
               static_cast<int>(100.0 * static_cast<double>(done_) / static_cast<double>(total_)),
               left.empty() ? "" : ", ", left.c_str());
  if (tty_) draw(false);  // the bar again, under the line
  std::fflush(stderr);
}

void Progress::advance(std::size_t units) {
  std::lock_guard lock(mutex_);
  done_ += units;
  if (done_ > total_) done_ = total_;
  if (observer_) observer_({units, done_, total_});
  const auto now = std::chrono::steady_clock::now();
  const auto interval = tty_ ? std::chrono::milliseconds(100) : std::chrono::milliseconds(5000);
  if (!estimated_ && g_enabled && done_ < total_) {
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    if (elapsed >= g_estimate_after_s && done_ > 0) {
      estimated_ = true;
      const double total_s = elapsed * static_cast<double>(total_) / static_cast<double>(done_);
      std::fprintf(
          stderr,
          "%s[crowdlab] %s: estimated %s in all for %zu steps (%zu done in %.1f s), %ld MB resident now\n",
          tty_ ? "\r\033[K" : "", label_.c_str(), duration_text(total_s).c_str(), total_, done_, elapsed,
          resident_mb());
    }
  }
  if (now - last_draw_ >= interval) {
    last_draw_ = now;
    draw(false);
  }
}

void Progress::finish() {
  std::lock_guard lock(mutex_);
  if (finished_) return;
  finished_ = true;
  draw(true);
}

void Progress::draw(bool final_line) {
  if (!g_enabled) return;
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double frac = static_cast<double>(done_) / static_cast<double>(total_);
  if (tty_) {
    constexpr int kWidth = 30;
    const int filled = static_cast<int>(frac * kWidth);
    std::string bar(static_cast<size_t>(filled), '#');
    bar.resize(kWidth, '.');
    const double eta = frac > 0 ? elapsed * (1.0 - frac) / frac : 0.0;
    std::fprintf(stderr, "\r%s [%s] %3d%% %zu/%zu  %.1fs%s", label_.c_str(), bar.c_str(),
                 static_cast<int>(frac * 100), done_, total_, final_line ? elapsed : eta,
                 final_line ? "      \n" : " left");
  } else {
    const std::string left = time_left(elapsed);
    const std::string eta = left.empty() ? "" : ", " + left;
    std::fprintf(stderr, "[crowdlab] %s: %zu/%zu (%d%%) %.1fs%s\n", label_.c_str(), done_, total_,
                 static_cast<int>(frac * 100), elapsed, final_line ? " done" : eta.c_str());
  }
  std::fflush(stderr);
}

}  // namespace crowdlab
