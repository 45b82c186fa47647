#include "framework/metrics/volume_index.hpp"

#include <cmath>
#include <string>

#include "framework/core/error.hpp"

namespace crowdlab {

double mean_cube_root_volume(std::span<const double> volume_per_frame_m3) {
  double sum = 0.0;
  int n = 0;
  for (size_t f = 0; f < volume_per_frame_m3.size(); ++f) {
    const double v = volume_per_frame_m3[f];
    if (!std::isfinite(v) || v < 0.0)
      throw InputError("mean_cube_root_volume: frame " + std::to_string(f) +
                       ": volume must be finite and >= 0");
    if (v == 0.0) continue;
    sum += std::cbrt(v);
    ++n;
  }
  return n == 0 ? 0.0 : sum / n;
}

}  // namespace crowdlab
