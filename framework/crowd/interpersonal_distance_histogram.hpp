#pragma once
// Distribution of interpersonal distances over a clip (seed 001 Figure 8, "distribution of
// interpersonal distances for the sets of trajectories"): every frame, every pair closer than
// max_distance_m contributes its root distance (or, with nearest_only, each agent contributes the
// distance to its nearest neighbour). Bins are [k w, (k + 1) w), k = 0 .. ceil(max / w) - 1.
#include <string>
#include <vector>

#include "framework/core/trajectories.hpp"

namespace crowdlab {

struct DistanceHistogram {
  double bin_width_m = 0.05;
  std::vector<long long> counts;  ///< per bin
  long long total = 0;
  double mean_m = 0.0;  ///< mean of the samples
};

DistanceHistogram interpersonal_distance_histogram(const CrowdTrajectories& trajectories,
                                                   double bin_width_m = 0.05, double max_distance_m = 2.0,
                                                   bool nearest_only = false);

/// CSV: bin_start_m,bin_end_m,count,fraction.
std::string distance_histogram_csv(const DistanceHistogram& histogram);

}  // namespace crowdlab
