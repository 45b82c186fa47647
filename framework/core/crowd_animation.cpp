#include "framework/core/crowd_animation.hpp"

#include <cmath>

#include "framework/core/error.hpp"
#include "framework/core/forward_kinematics.hpp"

namespace crowdlab {

void validate_crowd(const CrowdAnimation& crowd, const std::string& context) {
  if (!(crowd.meta.fps > 0.0) || !std::isfinite(crowd.meta.fps))
    throw InputError(context + ": fps must be a positive number");
  if (crowd.characters.empty()) throw InputError(context + ": the crowd has no characters");
  const size_t frames = crowd.characters.front().frames.size();
  if (frames == 0) throw InputError(context + ": the crowd has no frames");
  for (const CharacterAnimation& ch : crowd.characters) {
    const std::string who = context + ": character '" + ch.name + "'";
    if (ch.frames.size() != frames)
      throw InputError(who + " has " + std::to_string(ch.frames.size()) + " frames, expected " +
                       std::to_string(frames));
    validate_body_shape(ch.shape, who);
    if (ch.mesh) {
      validate_skinned_mesh(*ch.mesh, who);
      // The mesh is bound to this skeleton: its rest joints are the shape's rest joint positions.
      const std::array<Vec3, kJointCount> rest = joint_positions(ch.shape, Pose::rest(ch.shape));
      for (int j = 0; j < kJointCount; ++j) {
        if ((rest[static_cast<size_t>(j)] - ch.mesh->rest_joints_m[static_cast<size_t>(j)]).norm() > 1e-3)
          throw InputError(who + ": body mesh is bound to a different skeleton (joint '" +
                           std::string(joint_name(j)) + "' differs by more than 1 mm)");
      }
    }
    for (size_t f = 0; f < ch.frames.size(); ++f)
      validate_pose(ch.frames[f], who + " frame " + std::to_string(f));
  }
}

}  // namespace crowdlab
