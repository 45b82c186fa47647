#include "framework/animation/walk_from_clips.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "framework/animation/clip_loop.hpp"
#include "framework/animation/foot_track.hpp"
#include "framework/animation/pelvis_height_limit.hpp"
#include "framework/animation/reaction_pose.hpp"
#include "framework/animation/rotation_helpers.hpp"
#include "framework/animation/smoothed_track.hpp"
#include "framework/core/error.hpp"
#include "framework/core/forward_kinematics.hpp"
#include "framework/core/leg_ik.hpp"

namespace crowdlab {

using namespace anim;

namespace {

constexpr double kContactHeightM = 0.03;   // ball within 3 cm of its lowest height
constexpr double kContactSpeedMps = 0.35;  // ... and slower than this
constexpr double kMinCycleS = 0.6, kMaxCycleS = 2.0;
constexpr double kSwingLiftM = 0.06;  // peak ball lift of a planned swing
constexpr double kStandingSpeedMps = 0.05;

Vec3 ground(const Vec3& p) {
  return {p.x(), 0.0, p.z()};
}

/// Contact flags of one foot over a clip (see the header), with one-frame gaps closed.
std::vector<std::uint8_t> detect_contacts(const std::vector<Vec3>& ball, double fps) {
  const size_t n = ball.size();
  std::vector<double> speed(n, 0.0), slow_heights;
  for (size_t k = 0; k < n; ++k) {
    const size_t lo = k > 0 ? k - 1 : 0, hi = std::min(n - 1, k + 1);
    speed[k] = hi > lo ? (ball[hi] - ball[lo]).norm() * fps / static_cast<double>(hi - lo) : 0.0;
    if (speed[k] < kContactSpeedMps) slow_heights.push_back(ball[k].y());
  }
  std::vector<std::uint8_t> c(n, 0);
  if (slow_heights.empty()) return c;
  // The stance level: a low percentile of the heights where the ball is still (robust to the dips of
  // toe-off and to odd frames at a clip's ends).
  const size_t q = slow_heights.size() / 5;
  std::nth_element(slow_heights.begin(), slow_heights.begin() + static_cast<long>(q), slow_heights.end());
  const double level = slow_heights[q];
  for (size_t k = 0; k < n; ++k) c[k] = speed[k] < kContactSpeedMps && ball[k].y() < level + kContactHeightM;
  for (size_t k = 1; k + 1 < n; ++k)
    if (!c[k] && c[k - 1] && c[k + 1]) c[k] = 1;
  return c;
}

/// The cycle's pose at normalised phase u (linear / slerp between frames; the cycle wraps).
Pose sample_cycle(const WalkCycle& c, double u, std::array<double, 2>& contact) {
  const auto n = static_cast<long>(c.frames.size());
  const double t = frac(u) * static_cast<double>(n);
  const long i0 = static_cast<long>(std::floor(t)) % n, i1 = (i0 + 1) % n;
  const long nearest = static_cast<long>(std::lround(t)) % n;
  for (size_t s = 0; s < 2; ++s) contact[s] = c.contact[s][static_cast<size_t>(nearest)];
  return blend_poses(c.frames[static_cast<size_t>(i0)], c.frames[static_cast<size_t>(i1)], t - std::floor(t));
}

struct Blend {
  size_t a = 0, b = 0;  // indices into the speed-sorted cycles
  double w = 0.0;       // weight of b
};

Blend bracket(const std::vector<const WalkCycle*>& sorted, double v) {
  Blend r;
  if (v <= sorted.front()->speed_mps) return r;
  r.a = r.b = sorted.size() - 1;
  if (v >= sorted.back()->speed_mps) return r;
  for (size_t i = 0; i + 1 < sorted.size(); ++i)
    if (v < sorted[i + 1]->speed_mps) {
      r.a = i;
      r.b = i + 1;
      const double span = sorted[i + 1]->speed_mps - sorted[i]->speed_mps;
      r.w = span > 1e-9 ? (v - sorted[i]->speed_mps) / span : 0.0;
      break;
    }
  return r;
}

/// Ground distance per cycle at speed v: blended between bracketing cycles; outside the clips' range
/// the cadence changes with the square root of the speed ratio (stride ~ sqrt(v), cadence ~ sqrt(v),
/// the walk-ratio relation of gait_parameters.hpp).
double cycle_distance(const std::vector<const WalkCycle*>& sorted, double v) {
  const WalkCycle& lo = *sorted.front();
  const WalkCycle& hi = *sorted.back();
  if (v < lo.speed_mps) return lo.distance_m * std::sqrt(std::max(v, 1e-3) / lo.speed_mps);
  if (v > hi.speed_mps) return hi.distance_m * std::sqrt(v / hi.speed_mps);
  const Blend b = bracket(sorted, v);
  return (1.0 - b.w) * sorted[b.a]->distance_m + b.w * sorted[b.b]->distance_m;
}

}  // namespace

WalkCycle extract_walk_cycle(const RetargetedClip& clip, const BodyShape& shape, const std::string& source) {
  const size_t n = clip.frames.size();
  const double fps = clip.fps;
  if (!(fps > 0.0) || n < 3)
    throw InputError(source + ": walking clip has too few frames (" + std::to_string(n) + ")");
  std::array<std::vector<Vec3>, 2> ball;
  for (const Pose& p : clip.frames) {
    const std::array<Vec3, kJointCount> jp = joint_positions(shape, p);
    ball[0].push_back(jp[kLeftFoot]);
    ball[1].push_back(jp[kRightFoot]);
  }
  const std::array<std::vector<std::uint8_t>, 2> contact = {detect_contacts(ball[0], fps),
                                                            detect_contacts(ball[1], fps)};
  std::vector<size_t> onsets;
  for (size_t k = 1; k < n; ++k)
    if (contact[0][k] && !contact[0][k - 1]) onsets.push_back(k);
  long best_a = -1, best_b = -1;
  double best_distance = HUGE_VAL;
  for (size_t i = 0; i + 1 < onsets.size(); ++i) {
    const double duration = static_cast<double>(onsets[i + 1] - onsets[i]) / fps;
    if (duration < kMinCycleS || duration > kMaxCycleS) continue;
    const double mid = 0.5 * static_cast<double>(onsets[i] + onsets[i + 1]);
    if (std::abs(mid - 0.5 * static_cast<double>(n)) < best_distance) {
      best_distance = std::abs(mid - 0.5 * static_cast<double>(n));
      best_a = static_cast<long>(onsets[i]);
      best_b = static_cast<long>(onsets[i + 1]);
    }
  }
  if (best_a < 0) {
    size_t down = 0;
    for (auto v : contact[0]) down += v;
    throw InputError(source + ": no complete gait cycle found (two left-foot contacts " +
                     std::to_string(kMinCycleS).substr(0, 3) + "-" + std::to_string(kMaxCycleS).substr(0, 3) +
                     " s apart) in " + std::to_string(n) + " frames (left foot down in " +
                     std::to_string(down) + " frames, " + std::to_string(onsets.size()) +
                     " touch-downs); is it a walking clip?");
  }
  const auto a = static_cast<size_t>(best_a), b = static_cast<size_t>(best_b);
  const Vec3 start = ground(clip.frames[a].root_position_m), end = ground(clip.frames[b].root_position_m);
  const Vec3 travel = end - start;
  WalkCycle c;
  c.source = source;
  c.fps = fps;
  c.distance_m = travel.norm();
  c.speed_mps = c.distance_m * fps / static_cast<double>(b - a);
  if (c.distance_m < 0.2)
    throw InputError(source + ": the gait cycle at frames " + std::to_string(a) + "-" + std::to_string(b) +
                     " travels only " + std::to_string(c.distance_m) + " m; is it a walking clip?");
  const Quat inv = yaw(-heading_of(travel));
  // Travel-frame poses for frames a..b inclusive (b only to measure the loop mismatch).
  auto travel_pose = [&](size_t k) {
    const double u = static_cast<double>(k - a) / static_cast<double>(b - a);
    Pose p = clip.frames[k];
    const Vec3 line = start + u * travel;
    p.root_position_m = inv * (ground(p.root_position_m) - line) + Vec3(0, p.root_position_m.y(), 0);
    p.local_rotations[kPelvis] = (inv * p.local_rotations[kPelvis]).normalized();
    return p;
  };
  const Pose first = travel_pose(a), last = travel_pose(b);
  std::array<Quat, kJointCount> mismatch_inverse;
  for (size_t j = 0; j < kJointCount; ++j)
    mismatch_inverse[j] = (first.local_rotations[j] * last.local_rotations[j].conjugate()).normalized();
  const Vec3 root_mismatch = last.root_position_m - first.root_position_m;
  for (size_t k = a; k < b; ++k) {
    const double u = static_cast<double>(k - a) / static_cast<double>(b - a);
    Pose p = travel_pose(k);
    p.root_position_m -= u * root_mismatch;
    for (size_t j = 0; j < kJointCount; ++j)
      p.local_rotations[j] =
          (Quat::Identity().slerp(u, mismatch_inverse[j]) * p.local_rotations[j]).normalized();
    c.frames.push_back(p);
    c.contact[0].push_back(contact[0][k]);
    c.contact[1].push_back(contact[1][k]);
  }
  return c;
}

WalkResult animate_walking_from_clips(const BodyShape& shape, const std::vector<WalkCycle>& cycles,
                                      const AgentTrajectory& trajectory, double fps, double phase0,
                                      const std::vector<double>& reaction) {
  check_gait_inputs(trajectory, fps, reaction, "animate_walking_from_clips");
  const size_t n = trajectory.position_m.size();
  if (cycles.empty()) throw InputError("animate_walking_from_clips: no walking cycles");
  std::vector<const WalkCycle*> sorted;
  for (const WalkCycle& c : cycles) {
    if (c.frames.size() < 2 || !(c.speed_mps > 0.0)) throw InputError(c.source + ": empty walking cycle");
    sorted.push_back(&c);
  }
  std::stable_sort(sorted.begin(), sorted.end(),
                   [](const WalkCycle* x, const WalkCycle* y) { return x->speed_mps < y->speed_mps; });

  const PaddedTrack p = pad_and_smooth(trajectory, fps);
  const size_t m = p.pos.size();
  const auto pad = static_cast<size_t>(p.pad);

  // ---- phase: v / D(v) cycles per second; standing finishes the step to the next touch-down ------
  // A standing character keeps stepping at 80 % of the slowest cadence until the next touch-down of
  // either foot (phase 0: left, right_down: right), where double support begins, then holds there
  // with both feet planted.
  const WalkCycle& slow = *sorted.front();
  const double slow_rate = slow.fps / static_cast<double>(slow.frames.size());  // cycles per second
  double right_down = 0.5;
  for (size_t i = 1; i < slow.frames.size(); ++i)
    if (slow.contact[1][i] && !slow.contact[1][i - 1]) {
      right_down = static_cast<double>(i) / static_cast<double>(slow.frames.size());
      break;
    }
  std::vector<double> phase(m);
  std::vector<std::uint8_t> at_rest(m, 0);
  double ph = phase0;
  bool holding = false;
  for (size_t k = 0; k < m; ++k) {
    const double v = p.speed[k];
    if (v >= kStandingSpeedMps) {
      holding = false;
      ph += v / cycle_distance(sorted, v) / fps;
    } else if (!holding) {
      const double next = ph + 0.8 * slow_rate / fps;
      const double base = std::floor(ph);
      for (const double stop : {base + right_down, base + 1.0, base + 1.0 + right_down})
        if (ph < stop && next >= stop) {
          holding = true;
          ph = stop;
          break;
        }
      if (!holding) ph = next;
    }
    phase[k] = ph;
    at_rest[k] = holding ? 1 : 0;
  }

  // ---- blended clip poses in the world and the feet they ask for ----------------------------------
  const std::array<Vec3, kJointCount> rest = joint_positions(shape, Pose::rest(shape));
  std::vector<Pose> poses(m);
  std::array<std::vector<std::uint8_t>, 2> contact;
  std::array<std::vector<FootTarget>, 2> desired;
  for (auto& c : contact) c.resize(m);
  for (auto& d : desired) d.resize(m);
  for (size_t k = 0; k < m; ++k) {
    const Blend bl = bracket(sorted, p.speed[k]);
    std::array<double, 2> ca{}, cb{};
    const Pose pa = sample_cycle(*sorted[bl.a], phase[k], ca);
    const Pose pb = sample_cycle(*sorted[bl.b], phase[k], cb);
    Pose pose = blend_poses(pa, pb, bl.w);
    const Quat heading = yaw(p.heading[k]);
    const Vec3 offset = pose.root_position_m;
    pose.root_position_m =
        Vec3(p.pos[k].x(), offset.y(), p.pos[k].y()) + heading * Vec3(offset.x(), 0, offset.z());
    pose.local_rotations[kPelvis] = (heading * pose.local_rotations[kPelvis]).normalized();
    const size_t f = k >= pad && k - pad < n ? k - pad : n;
    if (f < n && !reaction.empty()) apply_reaction_upper_body(pose, std::clamp(reaction[f], -1.0, 1.0));
    const BoneTransforms bones = forward_kinematics(shape, pose);
    for (size_t s = 0; s < 2; ++s) {
      const LegJoints lj = leg_joints(s == 0 ? LegSide::kLeft : LegSide::kRight);
      contact[s][k] = at_rest[k] || (1.0 - bl.w) * ca[s] + bl.w * cb[s] >= 0.5 ? 1 : 0;
      FootTarget& d = desired[s][k];
      d.ball = bones[static_cast<size_t>(lj.foot)].translation;
      d.ball.y() = rest[static_cast<size_t>(lj.foot)].y();
      d.yaw_rad = heading_of(bones[static_cast<size_t>(lj.ankle)].rotation * Vec3::UnitZ());
      d.pitch_rad = 0.0;
      d.lift_m = kSwingLiftM;
    }
    poses[k] = pose;
  }
  std::array<std::vector<FootState>, 2> feet;
  for (size_t s = 0; s < 2; ++s)
    feet[s] = plan_foot_track(shape, s == 0 ? LegSide::kLeft : LegSide::kRight, contact[s], desired[s]);

  // ---- pelvis height where the legs cannot reach, then leg IK ---------------------------------------
  std::vector<double> root_h(m);
  std::vector<Quat> pelvis_rot(m);
  std::vector<Vec3> root_xz(m);
  for (size_t k = 0; k < m; ++k) {
    root_h[k] = poses[k].root_position_m.y();
    pelvis_rot[k] = poses[k].local_rotations[kPelvis];
    root_xz[k] = ground(poses[k].root_position_m);
  }
  limit_pelvis_height(shape, root_h, pelvis_rot, root_xz, {&feet[0], &feet[1]}, kLegReachFraction,
                      std::max(1, static_cast<int>(std::lround(0.12 * fps))));
  WalkResult out(n);
  for (size_t f = 0; f < n; ++f) {
    const size_t k = pad + f;
    Pose pose = poses[k];
    pose.root_position_m.y() = root_h[k];
    store_gait_frame(shape, pose, feet, k, f, out);
  }
  return out;
}

}  // namespace crowdlab
