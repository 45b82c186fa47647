#include "framework/animation/foot_skate.hpp"

#include <algorithm>

#include "framework/core/error.hpp"
#include "framework/core/forward_kinematics.hpp"

namespace crowdlab {

FootSkate measure_foot_skate(const BodyShape& shape, const std::vector<Pose>& frames,
                             const std::array<std::vector<std::uint8_t>, 2>& contact) {
  for (const auto& c : contact)
    if (c.size() != frames.size()) throw RuntimeError("measure_foot_skate: contact flags per frame required");
  FootSkate out;
  double sum = 0.0;
  const std::array<int, 2> ball = {kLeftFoot, kRightFoot};
  for (size_t side = 0; side < 2; ++side) {
    Vec3 start = Vec3::Zero();
    double worst = 0.0;
    bool open = false;
    for (size_t f = 0; f <= frames.size(); ++f) {
      const bool planted = f < frames.size() && contact[side][f];
      if (planted) {
        const Vec3 p = joint_positions(shape, frames[f])[static_cast<size_t>(ball[side])];
        if (!open) start = p, worst = 0.0, open = true;
        worst = std::max(worst, (p - start).norm());
        ++out.contact_frames;
      } else if (open) {
        open = false;
        ++out.intervals;
        sum += worst;
        out.max_m = std::max(out.max_m, worst);
      }
    }
  }
  out.mean_m = out.intervals > 0 ? sum / out.intervals : 0.0;
  return out;
}

}  // namespace crowdlab
