#include "framework/correction/anticipate_contacts.hpp"

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "framework/core/error.hpp"
#include "framework/core/skeleton.hpp"
#include "framework/correction/correct_crowd.hpp"
#include "framework/correction/follow_root_offsets.hpp"

namespace crowdlab {
namespace {

/// Rotation angle of a unit quaternion (rad, in [0, pi]; q and -q alike).
double turn_angle_rad(const Quat& q) {
  return 2.0 * std::atan2(q.vec().norm(), std::abs(q.w()));
}

/// The rotation from `from` toward `to` by at most `max_rad` along the shortest path.
Quat turn_toward(const Quat& from, const Quat& to, double max_rad) {
  const double gap = turn_angle_rad(from.conjugate() * to);
  if (gap <= max_rad) return to;
  return from.slerp(max_rad / gap, to).normalized();  // Eigen's slerp takes the shorter arc
}

/// Frames in visiting order, backward or forward; twice around when the clip loops, so that the frames
/// next to the seam see the deviations on its other side (the second lap's values are kept).
std::vector<size_t> visiting_order(size_t frames, bool backward, bool looping) {
  const size_t laps = looping ? 2 : 1;
  std::vector<size_t> order;
  order.reserve(laps * frames);
  for (size_t k = 0; k < laps * frames; ++k) order.push_back(backward ? frames - 1 - k % frames : k % frames);
  return order;
}

/// One pass of the dilation: each frame keeps its own deviation where that is at least as large as
/// the previous visited frame's turned toward it by max_rad, and that turned one otherwise.
std::vector<Quat> dilation_pass(const std::vector<Quat>& deviation, const std::vector<size_t>& order,
                                double max_rad) {
  std::vector<Quat> out = deviation;
  Quat previous = deviation[order.front()];
  for (const size_t f : order) {
    const Quat turned = turn_toward(previous, deviation[f], max_rad);
    previous = turn_angle_rad(deviation[f]) >= turn_angle_rad(turned) ? deviation[f] : turned;
    out[f] = previous;
  }
  return out;
}

/// The rate pass: each frame turns at most max_rad from the previous visited frame toward its own value.
std::vector<Quat> rate_pass(const std::vector<Quat>& ramp, const std::vector<size_t>& order, double max_rad) {
  std::vector<Quat> out = ramp;
  Quat previous = ramp[order.front()];
  for (const size_t f : order) {
    previous = turn_toward(previous, ramp[f], max_rad);
    out[f] = previous;
  }
  return out;
}

}  // namespace

std::vector<int> anticipated_joint_set(const std::string& name) {
  const std::vector<int> arms = {kLeftCollar,    kRightCollar, kLeftShoulder,
                                 kRightShoulder, kLeftElbow,   kRightElbow};
  const std::vector<int> trunk = {kSpine1, kSpine2, kSpine3, kNeck, kHead};
  const std::vector<int> legs = {kLeftHip, kRightHip, kLeftKnee, kRightKnee};
  auto joined = [](std::vector<int> a, const std::vector<int>& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
  };
  if (name == "none") return {};
  if (name == "arms") return arms;
  if (name == "upper") return joined(arms, trunk);
  if (name == "legs") return legs;
  if (name == "all") return joined(joined(arms, trunk), legs);
  throw InputError("corrector parameter anticipated_joints must be none, arms, upper, legs or all, got '" +
                   name + "'");
}

void validate_anticipation_params(const CorrectorParams& p) {
  anticipated_joint_set(p.anticipated_joints);
  if (!std::isfinite(p.anticipation_rate_radps) || p.anticipation_rate_radps <= 0.0)
    throw InputError("corrector parameter anticipation_rate_radps must be finite and > 0, got " +
                     std::to_string(p.anticipation_rate_radps));
  if (p.anticipation_runs < 1)
    throw InputError("corrector parameter anticipation_runs must be >= 1, got " +
                     std::to_string(p.anticipation_runs));
}

std::vector<Quat> ramp_deviations(const std::vector<Quat>& deviation, double max_turn_rad, bool looping) {
  if (deviation.size() < 2) return deviation;
  const std::vector<size_t> backward = visiting_order(deviation.size(), true, looping);
  const std::vector<size_t> forward = visiting_order(deviation.size(), false, looping);
  const std::vector<Quat> dilated =
      dilation_pass(dilation_pass(deviation, backward, max_turn_rad), forward, max_turn_rad);
  return rate_pass(dilated, forward, max_turn_rad);
}

void ramp_contact_deviations(const CrowdAnimation& input, const CrowdAnimation& corrected,
                             std::span<const int> joints, double max_turn_rad, bool looping,
                             CrowdAnimation& aims) {
  std::vector<Quat> deviation(static_cast<size_t>(input.frame_count()));
  for (size_t c = 0; c < input.characters.size(); ++c) {
    const std::vector<Pose>& in = input.characters[c].frames;
    const std::vector<Pose>& out = corrected.characters[c].frames;
    std::vector<Pose>& aim = aims.characters[c].frames;
    for (const int j : joints) {
      const auto jj = static_cast<size_t>(j);
      for (size_t f = 0; f < deviation.size(); ++f)
        deviation[f] = (in[f].local_rotations[jj].conjugate() * out[f].local_rotations[jj]).normalized();
      const std::vector<Quat> ramp = ramp_deviations(deviation, max_turn_rad, looping);
      for (size_t f = 0; f < deviation.size(); ++f)
        aim[f].local_rotations[jj] = (in[f].local_rotations[jj] * ramp[f]).normalized();
    }
  }
}

CrowdAnimation correct_crowd(const CrowdAnimation& crowd, const CorrectorParams& params, Progress* progress,
                             CorrectionReport* report) {
  const std::vector<int> joints = anticipated_joint_set(params.anticipated_joints);
  CorrectionReport last;
  CrowdAnimation out = correct_crowd_once(crowd, params, progress, &last);
  // The input the later runs aim at: the clip's own, or the one re-planned on the first run's roots.
  std::optional<CrowdAnimation> replanned;
  if (follows_root_offsets(crowd, params)) {
    FollowRootDef def;
    def.smoothing_s = params.follow_root_smoothing_s;
    replanned = follow_root_offsets(crowd, out, def, params);
    out = correct_crowd_once(*replanned, params, progress, &last);
  }
  const CrowdAnimation& input = replanned ? *replanned : crowd;
  const double max_turn_rad = params.anticipation_rate_radps / crowd.meta.fps;
  for (int run = 0; run < params.anticipation_runs && !joints.empty(); ++run) {
    // A clip the pre-roll closed into a loop is ramped around its seam.
    const bool looping = last.preroll_frames > 0 && last.loop_closure != "none";
    CrowdAnimation aims = input;
    ramp_contact_deviations(input, out, joints, max_turn_rad, looping, aims);
    out = correct_crowd_once(aims, params, nullptr, &last);
  }
  if (report) *report = last;
  return out;
}

}  // namespace crowdlab
