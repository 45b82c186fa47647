#include "framework/metrics/foot_contact_quality.hpp"

#include <algorithm>
#include <cmath>

#include "framework/core/forward_kinematics.hpp"
#include "framework/metrics/correction_quality.hpp"

namespace crowdlab {
namespace {

constexpr std::array<int, 4> kFootJoints = {kLeftAnkle, kRightAnkle, kLeftFoot, kRightFoot};
constexpr std::array<std::array<int, 2>, 2> kSideJoints = {
    {{kLeftAnkle, kLeftFoot}, {kRightAnkle, kRightFoot}}};

/// Lowest point (m) of one foot: its ankle bone's and ball bone's capsules.
double sole_height(const WorldCapsules& caps, int side) {
  double y = 1e9;
  for (int b : kSideJoints[static_cast<size_t>(side)]) {
    const Capsule& c = caps[static_cast<size_t>(b)];
    y = std::min(y, std::min(c.a.y(), c.b.y()) - c.radius_m);
  }
  return y;
}

/// How far (m, >= 0) each foot's capsules reach below the body's floor when it stands in its rest pose:
/// the floor is the rendered mesh's lowest rest vertex (a sole), and a foot capsule fitted around a shoe
/// wider than its foot reaches below it (`animation.collision_proxies: fitted`: 34-37 mm). That part is
/// proxy, not foot: the sole heights below add it back (sole_heights). 0 for bodies without a mesh and
/// for capsules above the floor (the volume-fitted ones).
std::array<double, 2> proxy_reach_below_floor(const CharacterAnimation& c) {
  std::array<double, 2> reach{};
  if (!c.mesh) return reach;
  const Pose rest = Pose::rest(c.shape);
  const BoneTransforms bones = forward_kinematics(c.shape, rest);
  double floor_y = 1e300;
  for (const Vec3& v : skin_vertices(*c.mesh, bones)) floor_y = std::min(floor_y, v.y());
  const WorldCapsules caps = world_capsules(c.shape, bones);
  for (int side = 0; side < 2; ++side)
    reach[static_cast<size_t>(side)] = std::max(0.0, floor_y - sole_height(caps, side));
  return reach;
}

/// The height (m) of each foot's sole on one frame: its capsules' lowest point plus their reach below the
/// rendered floor at rest, so that an input and a corrected animation carrying other capsules (`correct
/// --fit-proxies` on a crowd with volume-fitted ones) compare the same soles.
std::array<double, 2> sole_heights(const WorldCapsules& caps, const std::array<double, 2>& reach) {
  return {sole_height(caps, 0) + reach[0], sole_height(caps, 1) + reach[1]};
}

double horizontal(const Vec3& v) {
  return std::hypot(v.x(), v.z());
}

/// Samples of one character, appended to the crowd-wide lists.
struct Samples {
  std::vector<double> drift, penetration, below_input, floating;
};

/// How far the corrected sole is below the input's ground level for that foot: min(0, input sole), so a
/// foot the input itself puts below y = 0 counts only for what the correction adds (m, >= 0).
double depth_below_input(double sole_out_m, double sole_in_m) {
  return std::max(0.0, std::min(0.0, sole_in_m) - sole_out_m);
}

void measure_character(const CharacterAnimation& in, const CharacterAnimation& out, int character, int first,
                       double dt, FootContactQuality& q, Samples& s) {
  std::array<Vec3, kJointCount> prev_in{}, prev_out{};
  std::array<Vec3, 4> landing{};
  std::array<bool, 4> contact{};
  const int frames = static_cast<int>(in.frames.size());
  const std::array<double, 2> reach_in = proxy_reach_below_floor(in),
                              reach_out = proxy_reach_below_floor(out);
  for (int f = first; f < frames; ++f) {
    const Pose& pin_pose = in.frames[static_cast<size_t>(f)];
    const Pose& pout_pose = out.frames[static_cast<size_t>(f)];
    const auto pin = joint_positions(in.shape, pin_pose);
    const auto pout = joint_positions(out.shape, pout_pose);
    const WorldCapsules caps_out = world_capsules(out.shape, pout_pose);
    const WorldCapsules caps_in = world_capsules(in.shape, pin_pose);
    const std::array<double, 2> sole_in = sole_heights(caps_in, reach_in),
                                sole_out = sole_heights(caps_out, reach_out);
    std::array<bool, 2> side_contact{};
    for (int side = 0; side < 2; ++side) {
      const double depth = -sole_out[static_cast<size_t>(side)];
      if (depth > 0.0) s.penetration.push_back(depth);
      q.ground_penetration_max_m = std::max(q.ground_penetration_max_m, depth);
      const double added =
          depth_below_input(sole_out[static_cast<size_t>(side)], sole_in[static_cast<size_t>(side)]);
      if (added > 0.0) s.below_input.push_back(added);
      if (added > q.ground_penetration_added_max_m) {
        q.ground_penetration_added_max_m = added;
        q.ground_added_worst_character = character;
        q.ground_added_worst_joint = kSideJoints[static_cast<size_t>(side)][0];
        q.ground_added_worst_frame = f;
      }
    }
    if (f > first) {
      for (size_t k = 0; k < kFootJoints.size(); ++k) {
        const auto j = static_cast<size_t>(kFootJoints[k]);
        const double moved_in = (pin[j] - prev_in[j]).norm();
        const double excess = (pout[j] - prev_out[j]).norm() - moved_in;
        if (excess > q.pop_excess_max_m) {
          q.pop_excess_max_m = excess;
          q.pop_worst_character = character;
          q.pop_worst_joint = static_cast<int>(j);
          q.pop_worst_frame = f;
        }
        if (excess > kPopExcess_m) {
          ++q.foot_pops;
          q.pop_frames.push_back(f);
        }
        const bool now = moved_in < kContactSpeed_mps * dt && pin[j].y() < kContactHeight_m;
        if (now && !contact[k]) landing[k] = prev_out[j];
        contact[k] = now;
        if (!now) continue;
        ++q.contact_frames;
        s.drift.push_back(horizontal(pout[j] - landing[k]));
        side_contact[k % 2] = true;
      }
      for (int side = 0; side < 2; ++side) {
        if (!side_contact[static_cast<size_t>(side)]) continue;
        const double lift = sole_out[static_cast<size_t>(side)] - sole_in[static_cast<size_t>(side)];
        s.floating.push_back(std::max(0.0, lift));
      }
    }
    prev_in = pin;
    prev_out = pout;
  }
}

double max_of(const std::vector<double>& v) {
  return v.empty() ? 0.0 : *std::max_element(v.begin(), v.end());
}

}  // namespace

FootContactQuality measure_foot_contact_quality(const CrowdAnimation& input, const CrowdAnimation& corrected,
                                                int first_frame) {
  FootContactQuality q;
  Samples s;
  const double dt = input.meta.fps > 0.0 ? 1.0 / input.meta.fps : 0.0;
  for (size_t c = 0; c < input.characters.size(); ++c)
    measure_character(input.characters[c], corrected.characters[c], static_cast<int>(c),
                      std::max(0, first_frame), dt, q, s);
  std::sort(q.pop_frames.begin(), q.pop_frames.end());
  q.pop_frames.erase(std::unique(q.pop_frames.begin(), q.pop_frames.end()), q.pop_frames.end());
  q.stance_drift_p99_m = nearest_rank_quantile(s.drift, 0.99);
  q.stance_drift_max_m = max_of(s.drift);
  q.ground_penetration_p99_m = nearest_rank_quantile(s.penetration, 0.99);
  q.ground_penetration_added_p99_m = nearest_rank_quantile(s.below_input, 0.99);
  q.float_p99_m = nearest_rank_quantile(s.floating, 0.99);
  q.float_max_m = max_of(s.floating);
  return q;
}

}  // namespace crowdlab
