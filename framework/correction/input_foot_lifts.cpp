#include "framework/correction/input_foot_lifts.hpp"

#include "framework/core/forward_kinematics.hpp"
#include "framework/core/leg_ik.hpp"

namespace crowdlab {

std::array<std::vector<bool>, 2> lifted_frames(const CharacterAnimation& in, int first, int window,
                                               double max_step_m, const CorrectorParams& p) {
  std::array<std::vector<bool>, 2> lifted;
  auto before = joint_positions(in.shape, in.frames[static_cast<size_t>(first - 1)]);
  for (int k = 0; k < window; ++k) {
    const auto now = joint_positions(in.shape, in.frames[static_cast<size_t>(first + k)]);
    for (size_t s = 0; s < 2; ++s) {
      const LegJoints leg = leg_joints(kLegSides[s]);
      bool planted = false;
      for (int j : {leg.ankle, leg.foot}) {
        const auto ju = static_cast<size_t>(j);
        planted =
            planted || ((now[ju] - before[ju]).norm() < max_step_m && now[ju].y() < p.foot_plant_height_m);
      }
      lifted[s].push_back(!planted);
    }
    before = now;
  }
  return lifted;
}

}  // namespace crowdlab
