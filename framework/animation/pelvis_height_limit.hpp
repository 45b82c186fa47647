#pragma once
// Keeps both ankle targets reachable: lowers the root (pelvis) height where a leg would have to
// stretch beyond `reach_fraction` of its length, then smooths the result without ever raising it
// above the limit (a running minimum over +-r frames followed by a +-r box average is <= the limit at
// every frame, because each averaged minimum includes the frame itself). This lowering is what gives
// the procedural gait its vertical pelvis excursion at double support.
#include <array>
#include <vector>

#include "framework/animation/foot_track.hpp"

namespace crowdlab::anim {

/// The reach fraction both walk generators use: the knee stays a touch bent, never a locked leg.
inline constexpr double kLegReachFraction = 0.995;

/// root_height: (frames) nominal heights in, limited heights out (metres).
/// pelvis_rotation, root_xz: (frames) the pelvis world rotation and ground position (x, ·, z).
/// feet: per side, (frames) foot states whose ankles are the IK targets.
/// smoothing_radius: r in frames (>= 0).
void limit_pelvis_height(const BodyShape& shape, std::vector<double>& root_height,
                         const std::vector<Quat>& pelvis_rotation, const std::vector<Vec3>& root_xz,
                         const std::array<const std::vector<FootState>*, 2>& feet, double reach_fraction,
                         int smoothing_radius);

}  // namespace crowdlab::anim
