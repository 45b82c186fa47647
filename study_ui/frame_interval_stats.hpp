#pragma once
// frame_interval_stats: the per-trial playback timing the study window logs (frame_interval_*_ms
// columns): how regularly consecutive video frames were handed to the window. An interval well above
// the frame period (1000 / fps ms) means a frame stayed on screen too long; dropped frames are
// counted separately (the scheduler skips late frames to keep real time, see window_presenter.hpp).
#include <vector>

namespace crowdlab::study {

struct FrameIntervalStats {
  double mean_ms = -1.0;  ///< -1 each when fewer than two frames were shown
  double p99_ms = -1.0;   ///< 99th percentile, nearest-rank (the smallest interval >= 99 % of them)
  double max_ms = -1.0;
};

/// Statistics of the differences between consecutive hand-over times (ms, steady clock, ascending).
FrameIntervalStats frame_interval_stats(const std::vector<double>& handover_ms);

}  // namespace crowdlab::study
