#pragma once
// The exact contact of one bone capsule with one environment box (wall, barrier, stage; issue 27,
// seed 000 §3.4 body-environment contact). Used by the Newton step's penalty contacts
// (stage_narrow_phase.cpp) and by the depenetration pass (stage_depenetrate.cpp), so both push a
// capsule out of a box the same way.
//
//   axis outside the box:  penetration = -(min over the axis of sdf_box - r) (core capsule_box_distance),
//                          normal = the direction from the box's nearest point to that axis point
//                          (the gradient of sdf_box);
//   axis inside the box:   the capsule leaves by the face k, side s, that faces the body's root (the
//                          pelvis, outside walls and barriers): penetration = r + e_k - s x*_k,
//                          normal = s R_box e_k (x*: the axis point in the box frame, e: half extents),
//                          so an arm through a thin barrier comes back instead of going out the far side.
// Seed 000 point-samples the environment; on a 10 cm barrier through a capsule's axis the samples of
// both faces push opposite ways and cancel (docs/correction.md, issue 27).
#include "framework/core/capsule.hpp"
#include "framework/core/crowd_animation.hpp"

namespace crowdlab {

struct EnvironmentBoxContact {
  double penetration_m = 0.0;      ///< depth of the capsule behind the box surface (m; < 0: a gap)
  Vec3 normal = Vec3::UnitY();     ///< unit, world: the direction that takes the capsule out
  Vec3 axis_point = Vec3::Zero();  ///< the capsule axis point where the depth is measured (world, m)
};

/// Returns false (out untouched) when the capsule's penetration is not above min_penetration_m
/// (metres; -offset for contacts within an offset of the surface). root: the body's root (world, m).
bool environment_box_contact(const Capsule& capsule, const Box& box, const Vec3& root,
                             double min_penetration_m, EnvironmentBoxContact& out);

}  // namespace crowdlab
