#pragma once
// Foot skate: how far a foot that should be planted slides.
// For each foot and each contact interval (a maximal run of frames flagged in `contact`), the skate
// of the interval is the largest distance (metres, 3D) of the ball-of-foot joint (SMPL "foot") from
// its position on the interval's first frame. Heel rise about the ball leaves it at 0.
#include <array>
#include <cstdint>
#include <vector>

#include "framework/core/body_shape.hpp"
#include "framework/core/pose.hpp"

namespace crowdlab {

struct FootSkate {
  double max_m = 0.0;      ///< worst interval, both feet
  double mean_m = 0.0;     ///< mean over intervals of the per-interval skate
  int intervals = 0;       ///< contact intervals measured
  int contact_frames = 0;  ///< frames with a planted foot (either side)
};

/// contact: [left, right], one flag per frame of `frames`.
FootSkate measure_foot_skate(const BodyShape& shape, const std::vector<Pose>& frames,
                             const std::array<std::vector<std::uint8_t>, 2>& contact);

}  // namespace crowdlab
