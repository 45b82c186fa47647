#pragma once
// Test-only measures of correction quality, computed independently of the solver's own contact code:
//   overlap volume between characters (grid sampling of capsule unions, independent of metrics/'s
//   exact lens integration). Depths, rotation deviation and foot skate come from
//   framework/metrics/correction_quality.hpp (which does not use the solver either).
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "framework/core/crowd_animation.hpp"
#include "framework/core/forward_kinematics.hpp"
#include "framework/metrics/correction_quality.hpp"

namespace crowdlab::test {

inline bool inside_body(const WorldCapsules& caps, const Vec3& p) {
  for (const Capsule& c : caps) {
    const SegmentClosestPoints cp = segment_closest_points(c.a, c.b, p, p);
    if (cp.distance_m < c.radius_m) return true;
  }
  return false;
}

/// Total volume (m^3) of points lying inside two characters at once, summed over character pairs,
/// by sampling a grid of `step` metres over each pair's AABB intersection.
inline double overlap_volume(const std::vector<WorldCapsules>& bodies, double step = 0.02) {
  auto box = [](const WorldCapsules& caps, Vec3& lo, Vec3& hi) {
    lo = Vec3::Constant(1e300);
    hi = Vec3::Constant(-1e300);
    for (const Capsule& c : caps) {
      lo = lo.cwiseMin(c.a.cwiseMin(c.b) - Vec3::Constant(c.radius_m));
      hi = hi.cwiseMax(c.a.cwiseMax(c.b) + Vec3::Constant(c.radius_m));
    }
  };
  double volume = 0.0;
  for (size_t i = 0; i < bodies.size(); ++i)
    for (size_t j = i + 1; j < bodies.size(); ++j) {
      Vec3 lo_i, hi_i, lo_j, hi_j;
      box(bodies[i], lo_i, hi_i);
      box(bodies[j], lo_j, hi_j);
      const Vec3 lo = lo_i.cwiseMax(lo_j), hi = hi_i.cwiseMin(hi_j);
      if ((lo.array() >= hi.array()).any()) continue;
      for (double x = lo.x() + step / 2; x < hi.x(); x += step)
        for (double y = lo.y() + step / 2; y < hi.y(); y += step)
          for (double z = lo.z() + step / 2; z < hi.z(); z += step) {
            const Vec3 p(x, y, z);
            if (inside_body(bodies[i], p) && inside_body(bodies[j], p)) volume += step * step * step;
          }
    }
  return volume;
}

inline std::vector<WorldCapsules> frame_capsules(const CrowdAnimation& crowd, int frame) {
  std::vector<WorldCapsules> out;
  for (const CharacterAnimation& ch : crowd.characters)
    out.push_back(world_capsules(ch.shape, ch.frames[static_cast<size_t>(frame)]));
  return out;
}

/// Largest local-rotation deviation (degrees) over characters, frames and joints.
inline double max_rotation_deviation_deg(const CrowdAnimation& a, const CrowdAnimation& b) {
  double m = 0.0;
  for (size_t c = 0; c < a.characters.size(); ++c)
    for (size_t f = 0; f < a.characters[c].frames.size(); ++f)
      for (int j = 0; j < kJointCount; ++j)
        m = std::max(m,
                     rotation_angle_deg(a.characters[c].frames[f].local_rotations[static_cast<size_t>(j)],
                                        b.characters[c].frames[f].local_rotations[static_cast<size_t>(j)]));
  return m;
}

}  // namespace crowdlab::test
