#pragma once
// Capsules: the collision volume of one bone (seed 000 §3.4): all points within radius_m of the
// segment [a, b]. A capsule with a == b is a sphere.
#include "framework/core/math_types.hpp"

namespace crowdlab {

struct Capsule {
  Vec3 a = Vec3::Zero();  ///< segment start (metres), in the frame the capsule is expressed in
  Vec3 b = Vec3::Zero();  ///< segment end (metres)
  double radius_m = 0.0;  ///< radius (metres), > 0

  double length_m() const { return (b - a).norm(); }
  /// Exact volume of the capsule: cylinder + two hemispheres (m^3).
  double volume_m3() const;
  /// The capsule moved by a rigid transform (e.g. bone frame -> world frame).
  Capsule transformed(const RigidTransform& t) const { return {t.apply(a), t.apply(b), radius_m}; }
};

/// Closest points between segments [p0,p1] and [q0,q1].
///   s, t   : segment parameters in [0,1] of the closest points (point = p0 + s (p1 - p0), etc.)
///   distance_m : distance between the closest points.
/// Robust for degenerate (zero-length) and parallel segments: for parallel segments the midpoint of
/// the overlapping interval is chosen, so the result is continuous and symmetric.
struct SegmentClosestPoints {
  double s = 0.0;
  double t = 0.0;
  Vec3 point_on_p = Vec3::Zero();
  Vec3 point_on_q = Vec3::Zero();
  double distance_m = 0.0;
};
SegmentClosestPoints segment_closest_points(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1);

/// Penetration between two capsules (same frame).
///   depth_m : r_a + r_b - |closest points distance|; > 0 means overlap.
///   normal  : unit vector from capsule b toward capsule a along which separating a by depth_m
///             removes the overlap. When the axes intersect (distance 0) the normal is taken
///             perpendicular to both axes, or to axis a when they are parallel, so it is always defined.
///   point_a, point_b : the closest points on the two axes.
struct CapsuleContact {
  double depth_m = 0.0;
  Vec3 normal = Vec3::UnitY();
  Vec3 point_a = Vec3::Zero();
  Vec3 point_b = Vec3::Zero();
  double s = 0.0;  ///< parameter of point_a on capsule a's axis
  double t = 0.0;  ///< parameter of point_b on capsule b's axis
};
CapsuleContact capsule_contact(const Capsule& a, const Capsule& b);

/// A unit vector perpendicular to v (v need not be unit; must be non-zero).
Vec3 any_perpendicular(const Vec3& v);

}  // namespace crowdlab
