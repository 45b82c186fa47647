#include "framework/animation/foot_track.hpp"

#include <algorithm>
#include <cmath>

#include "framework/animation/rotation_helpers.hpp"
#include "framework/core/error.hpp"

namespace crowdlab::anim {

double solve_legs(const BodyShape& shape, Pose& pose, const FootState& left, const FootState& right) {
  double error = 0.0;
  for (const LegSide side : {LegSide::kLeft, LegSide::kRight}) {
    const FootState& fs = side == LegSide::kLeft ? left : right;
    const Vec3 foot_fwd = fs.rotation * Vec3::UnitZ();
    const Vec3 body_fwd = pose.local_rotations[kPelvis] * Vec3::UnitZ();
    const Vec3 pole(foot_fwd.x() + body_fwd.x(), 0, foot_fwd.z() + body_fwd.z());
    error = std::max(error, solve_leg_ik(shape, pose, side, fs.ankle, fs.rotation, pole));
    pose.local_rotations[static_cast<size_t>(leg_joints(side).foot)] = Quat::Identity();  // flat toes
  }
  return error;
}

Quat foot_rotation(double yaw_rad, double pitch_rad) {
  return (yaw(yaw_rad) * pitch(pitch_rad)).normalized();
}

namespace {
struct Interval {
  size_t first, last;  // inclusive frame range of one contact
};

std::vector<Interval> contact_intervals(const std::vector<std::uint8_t>& contact) {
  std::vector<Interval> out;
  for (size_t k = 0; k < contact.size(); ++k) {
    if (!contact[k]) continue;
    if (!out.empty() && out.back().last + 1 == k)
      out.back().last = k;
    else
      out.push_back({k, k});
  }
  return out;
}
}  // namespace

std::vector<FootState> plan_foot_track(const BodyShape& shape, LegSide side,
                                       const std::vector<std::uint8_t>& contact,
                                       const std::vector<FootTarget>& desired) {
  if (contact.size() != desired.size()) throw RuntimeError("plan_foot_track: contact/desired size mismatch");
  const size_t n = contact.size();
  std::vector<FootState> out(n);
  const std::vector<Interval> stances = contact_intervals(contact);

  // Planted foot of every interval, and the states of its frames.
  std::vector<Vec3> plant_ball(stances.size());
  std::vector<double> plant_yaw(stances.size());
  for (size_t i = 0; i < stances.size(); ++i) {
    const size_t mid = (stances[i].first + stances[i].last) / 2;
    plant_ball[i] = desired[mid].ball;
    plant_yaw[i] = desired[mid].yaw_rad;
    for (size_t k = stances[i].first; k <= stances[i].last; ++k) {
      FootState& s = out[k];
      s.contact = true;
      s.ball = plant_ball[i];
      s.rotation = foot_rotation(plant_yaw[i], desired[k].pitch_rad);
      s.ankle = ankle_from_ball(shape, side, s.ball, s.rotation);
    }
  }
  if (stances.empty()) {  // never on the ground: follow the desired values directly
    for (size_t k = 0; k < n; ++k) {
      out[k].rotation = foot_rotation(desired[k].yaw_rad, desired[k].pitch_rad);
      out[k].ball = desired[k].ball + Vec3(0, desired[k].lift_m, 0);
      out[k].ankle = ankle_from_ball(shape, side, out[k].ball, out[k].rotation);
    }
    return out;
  }
  // Before the first and after the last contact: hold.
  for (size_t k = 0; k < stances.front().first; ++k)
    out[k] = out[stances.front().first], out[k].contact = false;
  for (size_t k = stances.back().last + 1; k < n; ++k)
    out[k] = out[stances.back().last], out[k].contact = false;

  // Swings between consecutive contacts.
  for (size_t i = 0; i + 1 < stances.size(); ++i) {
    const size_t k0 = stances[i].last, k1 = stances[i + 1].first;
    if (k1 <= k0 + 1) continue;
    const FootState& a = out[k0];
    const FootState& b = out[k1];
    const double yaw0 = plant_yaw[i];
    const double dyaw = wrap_angle(plant_yaw[i + 1] - yaw0);
    const double pitch0 = desired[k0].pitch_rad;
    const double pitch1 = desired[k1].pitch_rad;
    double peak = 0;
    for (size_t k = k0 + 1; k < k1; ++k) peak = std::max(peak, desired[k].lift_m);
    for (size_t k = k0 + 1; k < k1; ++k) {
      const double s = static_cast<double>(k - k0) / static_cast<double>(k1 - k0);
      const double e = cosine_ease(s);
      // Toes stay down early in the swing, the foot levels off by 60 % of it.
      const double p = pitch0 * (1.0 - cosine_ease(s / 0.6)) + pitch1 * cosine_ease((s - 0.6) / 0.4);
      FootState& st = out[k];
      st.contact = false;
      st.rotation = foot_rotation(yaw0 + dyaw * e, p);
      st.ankle = a.ankle + (b.ankle - a.ankle) * e + Vec3(0, peak * std::sin(kPi * s), 0);
      st.ball = st.ankle + st.rotation * shape.joint_offsets_m[static_cast<size_t>(leg_joints(side).foot)];
    }
  }
  return out;
}

void store_gait_frame(const BodyShape& shape, Pose pose, const std::array<std::vector<FootState>, 2>& feet,
                      size_t k, size_t f, GaitFrames& out) {
  out.max_ik_error_m = std::max(out.max_ik_error_m, solve_legs(shape, pose, feet[0][k], feet[1][k]));
  for (size_t side = 0; side < 2; ++side) out.contact[side][f] = feet[side][k].contact ? 1 : 0;
  for (Quat& q : pose.local_rotations) q.normalize();
  out.frames[f] = pose;
}

}  // namespace crowdlab::anim
