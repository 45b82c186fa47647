#include "framework/animation/dance_animation.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "framework/animation/dance_motions.hpp"
#include "framework/animation/foot_track.hpp"
#include "framework/animation/pelvis_height_limit.hpp"
#include "framework/animation/rotation_helpers.hpp"
#include "framework/core/error.hpp"
#include "framework/core/forward_kinematics.hpp"
#include "framework/core/leg_ik.hpp"
#include "framework/core/seed.hpp"

namespace crowdlab {

using namespace anim;

DanceStyle dance_style_from_seed(std::uint64_t seed, double fit_loops_to_s) {
  Rng rng(derive_seed(seed, "dance-style"));
  DanceStyle s;
  s.motion = static_cast<int>(uniform_index(rng, dance_motions().size()));
  const DanceMotion& m = dance_motions()[static_cast<size_t>(s.motion)];
  s.tempo_bpm = (100.0 + 30.0 * uniform01(rng)) * (m.idle ? 0.5 : 1.0);
  s.phase_beats = m.loop_beats * uniform01(rng);
  s.amplitude = 0.75 + 0.5 * uniform01(rng);
  s.mirror = uniform01(rng) < 0.5;
  if (fit_loops_to_s > 0.0) {
    const double loops = std::max(1.0, std::round(fit_loops_to_s / dance_loop_period_s(s)));
    s.tempo_bpm = loops * m.loop_beats * 60.0 / fit_loops_to_s;
  }
  return s;
}

double dance_loop_period_s(const DanceStyle& style) {
  return dance_motions()[static_cast<size_t>(style.motion)].loop_beats * 60.0 / style.tempo_bpm;
}

namespace {
DancePose mirrored(const DancePose& p) {
  DancePose m = p;
  m.pelvis_offset.x() = -p.pelvis_offset.x();
  m.pelvis_yaw = -p.pelvis_yaw, m.pelvis_roll = -p.pelvis_roll;
  m.spine_yaw = -p.spine_yaw, m.spine_roll = -p.spine_roll;
  m.head_yaw = -p.head_yaw, m.head_roll = -p.head_roll;
  std::swap(m.arm[0], m.arm[1]);
  std::swap(m.foot[0], m.foot[1]);
  return m;
}
DanceResult animate_padded(const BodyShape& shape, const AgentTrajectory& anchor, double fps,
                           const DanceStyle& style, double first_frame);
}  // namespace

DanceResult animate_dancing(const BodyShape& shape, const AgentTrajectory& anchor, double fps,
                            const DanceStyle& style) {
  const size_t n = anchor.position_m.size();
  if (!(fps > 0) || !std::isfinite(fps)) throw InputError("animate_dancing: fps must be > 0");
  if (n == 0 || anchor.heading_rad.size() != n)
    throw InputError("animate_dancing: trajectory needs one position and heading per frame");
  if (style.motion < 0 || style.motion >= static_cast<int>(dance_motions().size()) ||
      !(style.tempo_bpm > 0) || !std::isfinite(style.amplitude) || !std::isfinite(style.phase_beats))
    throw InputError("animate_dancing: invalid dance style (motion " + std::to_string(style.motion) + ")");
  for (size_t k = 0; k < n; ++k)
    if (!anchor.position_m[k].allFinite() || !std::isfinite(anchor.heading_rad[k]))
      throw InputError("animate_dancing: trajectory frame " + std::to_string(k) + " is not finite");

  // Work on the clip padded by 2 s of held anchor at both ends, so that contact intervals, swings
  // and height smoothing near the clip's ends see the same neighbourhood as inside (a clip holding
  // whole loops then repeats exactly across its seam).
  const auto pad = static_cast<size_t>(std::lround(2.0 * fps));
  AgentTrajectory padded;
  for (size_t k = 0; k < n + 2 * pad; ++k) {
    const size_t src = k < pad ? 0 : std::min(k - pad, n - 1);
    padded.position_m.push_back(anchor.position_m[src]);
    padded.heading_rad.push_back(anchor.heading_rad[src]);
  }
  const DanceResult full = animate_padded(shape, padded, fps, style, static_cast<double>(pad));
  DanceResult out;
  out.max_ik_error_m = full.max_ik_error_m;
  out.frames.assign(full.frames.begin() + static_cast<std::ptrdiff_t>(pad),
                    full.frames.begin() + static_cast<std::ptrdiff_t>(pad + n));
  for (size_t s = 0; s < 2; ++s)
    out.contact[s].assign(full.contact[s].begin() + static_cast<std::ptrdiff_t>(pad),
                          full.contact[s].begin() + static_cast<std::ptrdiff_t>(pad + n));
  return out;
}

namespace {
DanceResult animate_padded(const BodyShape& shape, const AgentTrajectory& anchor, double fps,
                           const DanceStyle& style, double first_frame) {
  const size_t n = anchor.position_m.size();
  const DanceMotion& motion = dance_motions()[static_cast<size_t>(style.motion)];
  const std::array<Vec3, kJointCount> rest = joint_positions(shape, Pose::rest(shape));
  const double stance_half_width = 1.1 * std::abs(shape.joint_offsets_m[kLeftHip].x());

  std::vector<DancePose> dp(n);
  std::vector<double> heading(n);
  for (size_t k = 0; k < n; ++k) {
    const double time = (static_cast<double>(k) - first_frame) / fps;
    double beat = std::fmod(style.phase_beats + time * style.tempo_bpm / 60.0, motion.loop_beats);
    if (beat < 0) beat += motion.loop_beats;
    dp[k] = motion.evaluate(beat, style.amplitude);
    if (style.mirror) dp[k] = mirrored(dp[k]);
    heading[k] =
        k == 0 ? anchor.heading_rad[0] : heading[k - 1] + wrap_angle(anchor.heading_rad[k] - heading[k - 1]);
  }

  // Feet.
  std::array<std::vector<FootState>, 2> feet;
  for (int side = 0; side < 2; ++side) {
    const double sign = side == 0 ? 1.0 : -1.0;
    const LegSide sd = side == 0 ? LegSide::kLeft : LegSide::kRight;
    const LegJoints lj = leg_joints(sd);
    const Vec3 foot_off = shape.joint_offsets_m[static_cast<size_t>(lj.foot)];
    std::vector<std::uint8_t> contact(n);
    std::vector<FootTarget> desired(n);
    for (size_t k = 0; k < n; ++k) {
      const DanceFoot& f = dp[k].foot[static_cast<size_t>(side)];
      contact[k] = f.lift <= 0.0 ? 1 : 0;
      const double yaw_foot = heading[k] + sign * 6.0 * kPi / 180.0;
      const Vec3 ground(anchor.position_m[k].x(), 0, anchor.position_m[k].y());
      const Vec3 ankle = ground + yaw(heading[k]) * Vec3(sign * (stance_half_width + f.dx), 0, f.dz);
      desired[k].ball = ankle + yaw(yaw_foot) * Vec3(foot_off.x(), 0, foot_off.z());
      desired[k].ball.y() = rest[static_cast<size_t>(lj.foot)].y();
      desired[k].yaw_rad = yaw_foot;
      desired[k].pitch_rad = f.heel;
      desired[k].lift_m = f.lift;
    }
    feet[static_cast<size_t>(side)] = plan_foot_track(shape, sd, contact, desired);
  }

  std::vector<Quat> pelvis_rot(n);
  std::vector<Vec3> root_xz(n);
  std::vector<double> root_h(n);
  for (size_t k = 0; k < n; ++k) {
    const DancePose& p = dp[k];
    pelvis_rot[k] =
        (yaw(heading[k] + p.pelvis_yaw) * roll(p.pelvis_roll) * pitch(p.pelvis_pitch)).normalized();
    const Vec3 off = yaw(heading[k]) * Vec3(p.pelvis_offset.x(), 0, p.pelvis_offset.z());
    root_xz[k] = Vec3(anchor.position_m[k].x(), 0, anchor.position_m[k].y()) + off;
    root_h[k] = shape.pelvis_height_m() - 0.01 * shape.params.height_m + p.pelvis_offset.y();
  }
  limit_pelvis_height(shape, root_h, pelvis_rot, root_xz, {&feet[0], &feet[1]}, 0.985,
                      std::max(1, static_cast<int>(std::lround(0.05 * fps))));

  DanceResult out(n);
  for (size_t k = 0; k < n; ++k) {
    const DancePose& p = dp[k];
    Pose pose;
    pose.root_position_m = Vec3(root_xz[k].x(), root_h[k], root_xz[k].z());
    pose.local_rotations[kPelvis] = pelvis_rot[k];
    const std::array<double, 3> share = {0.3, 0.3, 0.4};
    const std::array<int, 3> spine = {kSpine1, kSpine2, kSpine3};
    for (size_t i = 0; i < 3; ++i)
      pose.local_rotations[static_cast<size_t>(spine[i])] =
          yaw(share[i] * p.spine_yaw) * roll(share[i] * p.spine_roll) * pitch(share[i] * p.spine_pitch);
    pose.local_rotations[kNeck] = yaw(0.4 * p.head_yaw) * roll(0.4 * p.head_roll) * pitch(0.4 * p.head_pitch);
    pose.local_rotations[kHead] = yaw(0.6 * p.head_yaw) * roll(0.6 * p.head_roll) * pitch(0.6 * p.head_pitch);
    for (int side = 0; side < 2; ++side) {
      const double s = side == 0 ? 1.0 : -1.0;
      const DanceArm& a = p.arm[static_cast<size_t>(side)];
      const Vec3 dir(s * std::sin(a.raise) * std::cos(a.plane), -std::cos(a.raise),
                     std::sin(a.raise) * std::sin(a.plane));
      pose.local_rotations[static_cast<size_t>(side == 0 ? kLeftCollar : kRightCollar)] = roll(s * a.shrug);
      pose.local_rotations[static_cast<size_t>(side == 0 ? kLeftShoulder : kRightShoulder)] =
          roll(-s * a.shrug) * shortest_arc(Vec3(s, 0, 0), dir);
      pose.local_rotations[static_cast<size_t>(side == 0 ? kLeftElbow : kRightElbow)] = yaw(-s * a.elbow);
    }
    store_gait_frame(shape, pose, feet, k, k, out);
  }
  return out;
}
}  // namespace

}  // namespace crowdlab
