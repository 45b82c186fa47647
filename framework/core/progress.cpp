#include "framework/core/progress.hpp"

#include <unistd.h>

#include <atomic>
#include <cstdio>

namespace crowdlab {
namespace {
std::atomic<bool> g_enabled{true};
}

void Progress::set_enabled(bool enabled) {
  g_enabled = enabled;
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

void Progress::advance(std::size_t units) {
  std::lock_guard lock(mutex_);
  done_ += units;
  if (done_ > total_) done_ = total_;
  const auto now = std::chrono::steady_clock::now();
  const auto interval = tty_ ? std::chrono::milliseconds(100) : std::chrono::milliseconds(5000);
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
    std::fprintf(stderr, "[crowdlab] %s: %zu/%zu (%d%%) %.1fs%s\n", label_.c_str(), done_, total_,
                 static_cast<int>(frac * 100), elapsed, final_line ? " done" : "");
  }
  std::fflush(stderr);
}

}  // namespace crowdlab
