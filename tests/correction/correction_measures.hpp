#pragma once
// Test-only measures of correction quality, computed independently of the solver's own contact code:
//   overlap volume between characters (grid sampling of capsule unions), inter-body penetration depths,
//   joint-rotation deviation, foot skate.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "framework/core/crowd_animation.hpp"
#include "framework/core/forward_kinematics.hpp"

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

/// Every positive capsule-capsule penetration depth between different characters (metres).
inline std::vector<double> inter_body_depths(const std::vector<WorldCapsules>& bodies) {
  std::vector<double> depths;
  for (size_t i = 0; i < bodies.size(); ++i)
    for (size_t j = i + 1; j < bodies.size(); ++j)
      for (const Capsule& a : bodies[i])
        for (const Capsule& b : bodies[j]) {
          const double d = capsule_contact(a, b).depth_m;
          if (d > 0.0) depths.push_back(d);
        }
  return depths;
}

inline double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t k = std::min(v.size() - 1, static_cast<size_t>(q * static_cast<double>(v.size() - 1) + 0.5));
  return v[k];
}

/// Angle (degrees) between two unit quaternions as rotations.
inline double rotation_angle_deg(const Quat& a, const Quat& b) {
  const double d = std::min(1.0, std::abs(a.normalized().dot(b.normalized())));
  return 2.0 * std::acos(d) * 180.0 / std::numbers::pi;
}

/// Mean over characters, frames and the 24 joints of the local-rotation deviation (degrees).
inline double mean_rotation_deviation_deg(const CrowdAnimation& a, const CrowdAnimation& b,
                                          int first_frame = 0) {
  double sum = 0.0;
  long count = 0;
  for (size_t c = 0; c < a.characters.size(); ++c)
    for (size_t f = static_cast<size_t>(first_frame); f < a.characters[c].frames.size(); ++f)
      for (int j = 0; j < kJointCount; ++j) {
        sum += rotation_angle_deg(a.characters[c].frames[f].local_rotations[static_cast<size_t>(j)],
                                  b.characters[c].frames[f].local_rotations[static_cast<size_t>(j)]);
        ++count;
      }
  return count ? sum / static_cast<double>(count) : 0.0;
}

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

/// Foot skate: the largest horizontal slide (metres) of a planted foot. A foot joint (ankle or ball)
/// counts as planted when, in the input, it stays within 1 mm of its first-frame position and below
/// 15 cm; its slide is the horizontal distance of the corrected joint from its corrected first-frame
/// position, maximised over frames, joints and characters.
inline double foot_skate_m(const CrowdAnimation& input, const CrowdAnimation& corrected) {
  double worst = 0.0;
  for (size_t c = 0; c < input.characters.size(); ++c) {
    const auto& ch_in = input.characters[c];
    const auto& ch_out = corrected.characters[c];
    const auto in0 = joint_positions(ch_in.shape, ch_in.frames.front());
    const auto out0 = joint_positions(ch_out.shape, ch_out.frames.front());
    for (int j : {kLeftAnkle, kRightAnkle, kLeftFoot, kRightFoot}) {
      const auto jj = static_cast<size_t>(j);
      bool planted = in0[jj].y() < 0.15;
      double slide = 0.0;
      for (size_t f = 0; f < ch_in.frames.size() && planted; ++f) {
        const auto pin = joint_positions(ch_in.shape, ch_in.frames[f]);
        const auto pout = joint_positions(ch_out.shape, ch_out.frames[f]);
        if ((pin[jj] - in0[jj]).norm() > 1e-3) planted = false;
        slide = std::max(slide, std::hypot(pout[jj].x() - out0[jj].x(), pout[jj].z() - out0[jj].z()));
      }
      if (planted) worst = std::max(worst, slide);
    }
  }
  return worst;
}

}  // namespace crowdlab::test
