#pragma once
// CrowdExtent: the plain data that decides how a viewpoint frames a crowd.
//
// The `baseline` and `ours` clips of one condition must be framed by the identical camera, or
// participants could see a difference that is not the method (issue 17). So the framing is computed
// from data the two methods share: the crowd stage's trajectories (2D, or the 3D surface frames of a
// manifold crowd) and the characters' body heights, which the correction stage never changes.
// A lone crowd file (`crowdlab render CROWD.glb`) can be framed from its own root motion instead.
//
// The box is the axis-aligned bound of every character's body cylinder at every frame: radius
// kBodyRadiusM around the body axis (half a shoulder width plus arm reach), from the feet to the top
// of the head (height_m along the body's up vector).
//
// A crowd that travels (its centroid moves more than kFollowTravelM between the first and the last
// frame: the corridor's walkers cover ~26 m in 20 s) cannot be framed by one box over the whole clip
// (issue 28: the crowd starts as a speck, or walks through the camera). For it the extent also holds a
// follow path, the crowd's centroid smoothed over +-1 s, and the box of the bodies relative to that
// path: the viewpoints then follow the crowd (viewpoint.hpp).
#include <vector>

#include "framework/core/crowd_animation.hpp"
#include "framework/core/surface_trajectories.hpp"
#include "framework/core/trajectories.hpp"

namespace crowdlab::stimuli {

/// Radius of the cylinder that bounds a body around its axis (metres).
inline constexpr double kBodyRadiusM = 0.4;
/// Centroid travel over the clip beyond which the framing follows the crowd (metres): a swaying or
/// dancing crowd moves centimetres, a walking one metres.
inline constexpr double kFollowTravelM = 1.0;

/// One character's shared motion, per frame.
struct CharacterTrack {
  std::vector<Vec3> feet_m;   ///< (frames) point under the feet, world frame, metres
  std::vector<Vec3> up;       ///< (frames) unit body axis, feet to head; empty: +Y at every frame
  std::vector<Vec3> forward;  ///< (frames) unit facing direction
  double height_m = 1.75;     ///< standing height, feet to the top of the head (metres)
};

struct CrowdExtent {
  Vec3 lo_m = Vec3::Zero(), hi_m = Vec3::Zero();  ///< bounding box of all body cylinders (metres)
  Vec3 front = Vec3::UnitZ();      ///< mean horizontal facing (unit); +Z when facings cancel (|mean| < 0.25)
  Vec3 walk_axis = Vec3::UnitX();  ///< principal horizontal direction of motion (unit)
  std::vector<Vec3> focal_feet_m;  ///< (frames) feet of the focal character (the first, "c000")
  Vec3 focal_forward = Vec3::UnitZ();  ///< horizontal facing of the focal character at frame 0 (unit)
  double fps = 30.0;
  /// (frames) a travelling crowd's centroid (feet, y = 0), smoothed over +-1 s (a window that shrinks
  /// symmetrically at the ends); empty when the crowd stays put (travel <= kFollowTravelM).
  std::vector<Vec3> follow_path_m;
  /// Box of all body cylinders relative to follow_path_m at their frame (metres; set when following).
  Vec3 follow_lo_m = Vec3::Zero(), follow_hi_m = Vec3::Zero();
};

/// The extent of `tracks` (all with the same number of frames >= 1; the first is the focal one).
/// Throws InputError when there is no track, no frame, or the frame counts differ.
CrowdExtent crowd_extent(const std::vector<CharacterTrack>& tracks, double fps);

/// Tracks of a flat crowd: ground positions (x, 0, z), facing from heading_rad, one height per agent.
/// Throws InputError when heights_m.size() != number of agents.
std::vector<CharacterTrack> character_tracks(const CrowdTrajectories& trajectories,
                                             const std::vector<double>& heights_m);
/// Tracks of a crowd on a surface (seed 002): feet, up and forward from the surface frames.
std::vector<CharacterTrack> character_tracks(const SurfaceTrajectories& surface,
                                             const std::vector<double>& heights_m);
/// Tracks read from an animation's roots (feet = pelvis minus its rest height, body axis +Y):
/// for a lone crowd file only; the pipeline frames from the shared trajectories.
std::vector<CharacterTrack> character_tracks(const CrowdAnimation& crowd);

/// Each character's standing height (shape.params.height_m), in character order.
std::vector<double> body_heights_m(const CrowdAnimation& crowd);

}  // namespace crowdlab::stimuli
