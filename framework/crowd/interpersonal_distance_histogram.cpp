#include "framework/crowd/interpersonal_distance_histogram.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "framework/core/csv.hpp"
#include "framework/core/error.hpp"
#include "framework/crowd/pair_closest_approaches.hpp"

namespace crowdlab {

DistanceHistogram interpersonal_distance_histogram(const CrowdTrajectories& t, double w, double max_d,
                                                   bool nearest_only) {
  if (!(w > 0.0) || !std::isfinite(w)) throw InputError("distance histogram: bin width must be > 0 m");
  if (!(max_d > 0.0) || !std::isfinite(max_d))
    throw InputError("distance histogram: maximum distance must be > 0 m");
  DistanceHistogram h;
  h.bin_width_m = w;
  const auto bins = static_cast<std::size_t>(std::ceil(max_d / w - 1e-9));
  h.counts.assign(bins, 0);
  double sum = 0.0;
  auto add = [&](double d) {
    const auto k = static_cast<std::size_t>(d / w);
    if (k >= bins) return;
    ++h.counts[k];
    ++h.total;
    sum += d;
  };
  const std::size_t n = t.agents.size();
  std::vector<double> nearest(n);
  for (int f = 0; f < t.frame_count(); ++f) {
    std::fill(nearest.begin(), nearest.end(), std::numeric_limits<double>::infinity());
    for_each_close_pair(t, f, max_d, [&](int i, int j, double d) {
      if (nearest_only) {
        nearest[static_cast<std::size_t>(i)] = std::min(nearest[static_cast<std::size_t>(i)], d);
        nearest[static_cast<std::size_t>(j)] = std::min(nearest[static_cast<std::size_t>(j)], d);
      } else {
        add(d);
      }
    });
    if (nearest_only)
      for (double d : nearest)
        if (std::isfinite(d)) add(d);
  }
  h.mean_m = h.total > 0 ? sum / static_cast<double>(h.total) : 0.0;
  return h;
}

std::string distance_histogram_csv(const DistanceHistogram& h) {
  std::string s = csv_line({"bin_start_m", "bin_end_m", "count", "fraction"});
  for (std::size_t k = 0; k < h.counts.size(); ++k)
    s += csv_line(
        {csv_number(k * h.bin_width_m), csv_number((k + 1) * h.bin_width_m), std::to_string(h.counts[k]),
         csv_number(h.total > 0 ? static_cast<double>(h.counts[k]) / static_cast<double>(h.total) : 0.0)});
  return s;
}

}  // namespace crowdlab
