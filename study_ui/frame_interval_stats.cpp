#include "study_ui/frame_interval_stats.hpp"

#include <algorithm>
#include <cmath>

namespace crowdlab::study {

FrameIntervalStats frame_interval_stats(const std::vector<double>& handover_ms) {
  FrameIntervalStats s;
  if (handover_ms.size() < 2) return s;
  std::vector<double> d(handover_ms.size() - 1);
  for (size_t i = 1; i < handover_ms.size(); ++i) d[i - 1] = handover_ms[i] - handover_ms[i - 1];
  double sum = 0.0;
  for (double v : d) sum += v;
  s.mean_ms = sum / static_cast<double>(d.size());
  std::sort(d.begin(), d.end());
  const size_t rank = static_cast<size_t>(std::ceil(0.99 * static_cast<double>(d.size())));  // 1-based
  s.p99_ms = d[std::max<size_t>(rank, 1) - 1];
  s.max_ms = d.back();
  return s;
}

}  // namespace crowdlab::study
