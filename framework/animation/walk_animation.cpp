#include "framework/animation/walk_animation.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "framework/animation/foot_track.hpp"
#include "framework/animation/gait_parameters.hpp"
#include "framework/animation/pelvis_height_limit.hpp"
#include "framework/animation/reaction_pose.hpp"
#include "framework/animation/rotation_helpers.hpp"
#include "framework/animation/smoothed_track.hpp"
#include "framework/core/error.hpp"
#include "framework/core/forward_kinematics.hpp"
#include "framework/core/leg_ik.hpp"
#include "framework/core/seed.hpp"

namespace crowdlab {

using namespace anim;

WalkStyle walk_style_from_seed(std::uint64_t seed) {
  Rng rng(derive_seed(seed, "walk-style"));
  WalkStyle s;
  s.phase0 = uniform01(rng);
  s.arm_swing_scale = 0.75 + 0.5 * uniform01(rng);
  s.sway_scale = 0.8 + 0.4 * uniform01(rng);
  s.idle_phase = uniform01(rng);
  return s;
}

namespace {

constexpr double kDeg = kPi / 180.0;
constexpr double kGravity = 9.81;

bool in_swing(double phase) {
  const double f = phase - std::floor(phase);
  const double g = f + 0.5 - std::floor(f + 0.5);
  return f >= kStanceFraction || g >= kStanceFraction;
}

// Gait phase per padded frame (see the header for the rules).
std::vector<double> integrate_phase(const PaddedTrack& p, double fps, double height_m, double phase0) {
  const size_t m = p.pos.size();
  std::vector<double> phase(m);
  const double slow_rate = gait_parameters(kMinGaitSpeed, height_m).stride_frequency_hz;
  double ph = phase0;
  Vec2 anchor_pos = p.pos.front();
  double anchor_heading = p.heading.front();
  double stepping_until = -1.0;
  for (size_t k = 0; k < m; ++k) {
    phase[k] = ph;
    const double a = activity_of_speed(p.speed[k]);
    double rate = a * gait_parameters(p.speed[k], height_m).stride_frequency_hz;
    if (a > 0.05) {
      anchor_pos = p.pos[k];
      anchor_heading = p.heading[k];
      stepping_until = -1.0;
    } else if (ph >= stepping_until && !in_swing(ph) &&
               ((p.pos[k] - anchor_pos).norm() > 0.15 ||
                std::abs(p.heading[k] - anchor_heading) > 25.0 * kDeg)) {
      stepping_until = ph + 1.0;
      anchor_pos = p.pos[k];
      anchor_heading = p.heading[k];
    }
    if (ph < stepping_until) rate = std::max(rate, 0.8 * slow_rate);
    if (in_swing(ph)) rate = std::max(rate, slow_rate);
    ph += rate / fps;
  }
  return phase;
}

}  // namespace

WalkResult animate_walking(const BodyShape& shape, const AgentTrajectory& trajectory, double fps,
                           const WalkStyle& style, const std::vector<double>& reaction) {
  check_gait_inputs(trajectory, fps, reaction, "animate_walking");
  const size_t n = trajectory.position_m.size();

  const double height = shape.params.height_m;
  const PaddedTrack p = pad_and_smooth(trajectory, fps);
  const size_t m = p.pos.size();
  const auto pad = static_cast<size_t>(p.pad);
  const std::vector<double> phase = integrate_phase(p, fps, height, style.phase0);
  std::vector<double> activity(m);
  for (size_t k = 0; k < m; ++k) activity[k] = activity_of_speed(p.speed[k]);

  const std::array<Vec3, kJointCount> rest = joint_positions(shape, Pose::rest(shape));
  const double hip_half_width = std::abs(shape.joint_offsets_m[kLeftHip].x());

  // ---- feet: contacts and desired plants ------------------------------------------------------
  std::array<std::vector<FootState>, 2> feet;
  for (LegSide side : {LegSide::kLeft, LegSide::kRight}) {
    const int si = side == LegSide::kLeft ? 0 : 1;
    const double sign = side == LegSide::kLeft ? 1.0 : -1.0;
    const double offset = side == LegSide::kLeft ? 0.0 : 0.5;
    const LegJoints lj = leg_joints(side);
    const Vec3 ball_rest = rest[static_cast<size_t>(lj.foot)];
    const Vec3 foot_off = shape.joint_offsets_m[static_cast<size_t>(lj.foot)];
    std::vector<std::uint8_t> contact(m);
    std::vector<FootTarget> desired(m);
    for (size_t k = 0; k < m; ++k) {
      const double u = frac(phase[k] + offset);
      contact[k] = u < kStanceFraction ? 1 : 0;
      const GaitParameters g = gait_parameters(p.speed[k], height);
      const double a = activity[k];
      const double h = p.heading[k];
      const double yaw_foot = h + sign * 4.0 * kDeg;
      const double lateral = sign * hip_half_width * (1.0 - 0.45 * a);
      const double back = -0.07 * 2.0 * g.step_length_m * a;
      const Vec3 ankle_ground = Vec3(p.pos[k].x(), 0, p.pos[k].y()) + yaw(h) * Vec3(lateral, 0, back);
      FootTarget& d = desired[k];
      d.yaw_rad = yaw_foot;
      d.ball = ankle_ground + yaw(yaw_foot) * Vec3(foot_off.x(), 0, foot_off.z());
      d.ball.y() = ball_rest.y();
      const double stance_progress = u / kStanceFraction;
      d.pitch_rad =
          contact[k] ? g.toe_off_pitch_rad * a * smoothstep01((stance_progress - 0.55) / 0.45) : 0.0;
      d.lift_m = g.foot_lift_m * (0.5 + 0.5 * a);
    }
    feet[static_cast<size_t>(si)] = plan_foot_track(shape, side, contact, desired);
  }

  // ---- pelvis orientation, ground position and height ----------------------------------------
  std::vector<Quat> pelvis_rot(m);
  std::vector<Vec3> root_xz(m);
  std::vector<double> root_h(m);
  std::vector<GaitParameters> gait(m);
  for (size_t k = 0; k < m; ++k) {
    const double a = activity[k] * style.sway_scale;
    gait[k] = gait_parameters(p.speed[k], height);
    const double c = std::cos(2 * kPi * phase[k]), s = std::sin(2 * kPi * phase[k]);
    const double rot = -gait[k].pelvic_rotation_rad * c * a;
    const double list = gait[k].pelvic_list_rad * s * a;
    const double lean = -std::atan(std::clamp(p.speed[k] * p.turn_rate[k] / kGravity, -0.25, 0.25));
    pelvis_rot[k] = (yaw(p.heading[k] + rot) * roll(list + lean)).normalized();
    const Vec3 sway = yaw(p.heading[k]) * Vec3(gait[k].lateral_sway_m * s * a, 0, 0);
    root_xz[k] = Vec3(p.pos[k].x(), 0, p.pos[k].y()) + sway;
    root_h[k] = shape.pelvis_height_m() - 0.005 * height;
  }
  // The reaction rotates the pelvis too; include it before limiting the height.
  for (size_t f = 0; f < n && !reaction.empty(); ++f)
    pelvis_rot[pad + f] =
        (pelvis_rot[pad + f] * yaw(std::clamp(reaction[f], -1.0, 1.0) * 5.0 * kDeg)).normalized();
  limit_pelvis_height(shape, root_h, pelvis_rot, root_xz, {&feet[0], &feet[1]}, kLegReachFraction,
                      std::max(1, static_cast<int>(std::lround(0.12 * fps))));

  // ---- poses -------------------------------------------------------------------------------------
  WalkResult out(n);
  const int look = static_cast<int>(std::lround(0.4 * fps));
  for (size_t f = 0; f < n; ++f) {
    const size_t k = pad + f;
    const double a = activity[k];
    const GaitParameters& g = gait[k];
    const double c = std::cos(2 * kPi * phase[k]);
    const double w = reaction.empty() ? 0.0 : std::clamp(reaction[f], -1.0, 1.0);
    const double t = static_cast<double>(f) / fps;
    Pose pose;
    pose.root_position_m = Vec3(root_xz[k].x(), root_h[k], root_xz[k].z());
    pose.local_rotations[kPelvis] = pelvis_rot[k] * yaw(-w * 5.0 * kDeg);  // reaction re-added below
    // Trunk: counter-rotate the thorax (net -50 % of the pelvic rotation), undo most of the list, lean.
    const double rot = -g.pelvic_rotation_rad * c * a * style.sway_scale;
    const double list = g.pelvic_list_rad * std::sin(2 * kPi * phase[k]) * a * style.sway_scale;
    const double breathe = (1.0 - a) * 1.5 * kDeg * std::sin(2 * kPi * (t / 4.0 + style.idle_phase));
    pose.local_rotations[kSpine1] = yaw(-0.45 * rot) * roll(-0.4 * list) * pitch(g.trunk_lean_rad * a);
    pose.local_rotations[kSpine2] = yaw(-0.45 * rot) * roll(-0.3 * list);
    pose.local_rotations[kSpine3] = yaw(-0.6 * rot) * pitch(breathe);
    // Head: look into the turn, 0.4 s ahead; idle look-around when standing.
    const size_t ahead = std::min(m - 1, k + static_cast<size_t>(look));
    const double look_yaw = std::clamp(p.heading[ahead] - p.heading[k], -0.5, 0.5) +
                            (1.0 - a) * 12.0 * kDeg * std::sin(2 * kPi * (t / 7.0 + style.idle_phase));
    pose.local_rotations[kNeck] = yaw(0.4 * (look_yaw + 0.5 * rot));
    pose.local_rotations[kHead] = yaw(0.6 * (look_yaw + 0.5 * rot)) * pitch(3.0 * kDeg);
    // Arms: contralateral swing; left arm forward when the right leg is forward.
    const double swing = g.arm_swing_rad * a * style.arm_swing_scale * reaction_arm_swing_factor(w);
    const double abduction = 8.0 * kDeg;
    for (int side = 0; side < 2; ++side) {
      const double sgn = side == 0 ? 1.0 : -1.0;
      const double theta = -sgn * swing * c;  // > 0: arm forward
      const double elbow = g.elbow_mean_rad * (0.5 + 0.5 * a) +
                           (swing > 0 ? g.elbow_swing_rad * a * theta / std::max(swing, 1e-9) : 0.0);
      const int sh = side == 0 ? kLeftShoulder : kRightShoulder;
      const int el = side == 0 ? kLeftElbow : kRightElbow;
      pose.local_rotations[static_cast<size_t>(sh)] = pitch(-theta) * roll(-sgn * (kPi / 2 - abduction));
      pose.local_rotations[static_cast<size_t>(el)] = yaw(-sgn * std::max(0.0, elbow));
    }
    apply_reaction_upper_body(pose, w);
    store_gait_frame(shape, pose, feet, k, f, out);  // legs
  }
  return out;
}

}  // namespace crowdlab
