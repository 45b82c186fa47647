#pragma once
// Signed distance between a capsule and a static oriented box (issue 27: body-environment contact of
// seed 000 §3.4 on the walls, barriers and stage boxes, measured exactly rather than point-sampled).
//
//   sdf_box(p)  the usual signed distance of point p to the box (m): the distance to the surface,
//               negative inside (e.g. Quilez, "Distance functions", the box case).
//   capsule_box_distance(capsule, box)
//     distance_m  min over the capsule axis of sdf_box(x) - radius: > 0 the gap between the capsule's
//                 surface and the box, < 0 the depth of the capsule's deepest point behind the box
//                 surface (its penetration, m)
//     axis_point  the point of the axis where that minimum is (world, m)
// sdf_box is convex (the distance to a convex set), so along the axis segment it is a convex function
// of the segment parameter and golden-section search finds its minimum (Kiefer 1953); 48 iterations
// narrow the parameter to 1e-10 of the axis length. Inputs and outputs in world coordinates (metres).
#include "framework/core/aabb.hpp"
#include "framework/core/capsule.hpp"
#include "framework/core/crowd_animation.hpp"

namespace crowdlab {

/// Signed distance (m) of world point p to the box: > 0 outside, < 0 inside.
double sdf_box(const Box& box, const Vec3& p);

struct CapsuleBoxDistance {
  double distance_m = 0.0;         ///< gap (> 0) or minus the penetration depth (< 0), metres
  Vec3 axis_point = Vec3::Zero();  ///< the axis point nearest the box (world, m)
};

CapsuleBoxDistance capsule_box_distance(const Capsule& capsule, const Box& box);

/// The world axis-aligned bounds of the box (m).
Aabb box_bounds(const Box& box);

}  // namespace crowdlab
