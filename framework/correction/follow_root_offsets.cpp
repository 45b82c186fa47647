#include "framework/correction/follow_root_offsets.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "framework/core/forward_kinematics.hpp"
#include "framework/core/leg_ik.hpp"
#include "framework/correction/blend_keeping_planted_feet.hpp"
#include "framework/correction/input_foot_lifts.hpp"

namespace crowdlab {
namespace {

Vec3 horizontal(const Vec3& v) {
  return {v.x(), 0.0, v.z()};
}

/// The first correction's horizontal root offsets, Gaussian-smoothed over time.
std::vector<Vec3> smoothed_root_offsets(const CharacterAnimation& in, const CharacterAnimation& out,
                                        double sigma_frames) {
  const int n = static_cast<int>(in.frames.size());
  std::vector<Vec3> raw(n);
  for (int f = 0; f < n; ++f)
    raw[f] = horizontal(out.frames[f].root_position_m - in.frames[f].root_position_m);
  if (sigma_frames <= 0.0) return raw;
  const int reach = static_cast<int>(std::ceil(3.0 * sigma_frames));
  std::vector<Vec3> smooth(n, Vec3::Zero());
  for (int f = 0; f < n; ++f) {
    double weight_sum = 0.0;
    for (int k = std::max(0, f - reach); k <= std::min(n - 1, f + reach); ++k) {
      const double d = (k - f) / sigma_frames;
      const double w = std::exp(-0.5 * d * d);
      smooth[f] += w * raw[k];
      weight_sum += w;
    }
    smooth[f] /= weight_sum;
  }
  return smooth;
}

/// Per side and frame, whether the input plants that foot (ankle or ball), by the corrector's test
/// (input_foot_lifts.hpp); frame 0 as frame 1.
std::array<std::vector<bool>, 2> planted_frames(const CharacterAnimation& in, double fps,
                                                const CorrectorParams& p) {
  const int n = static_cast<int>(in.frames.size());
  std::array<std::vector<bool>, 2> planted;
  if (n < 2) return {std::vector<bool>(static_cast<size_t>(n)), std::vector<bool>(static_cast<size_t>(n))};
  const std::array<std::vector<bool>, 2> lifted =
      lifted_frames(in, 1, n - 1, p.foot_plant_speed_mps / fps, p);
  for (size_t side = 0; side < 2; ++side) {
    planted[side] = {!lifted[side].front()};
    for (const bool l : lifted[side]) planted[side].push_back(!l);
  }
  return planted;
}

/// The foot's offset per frame: one per planted stretch (the root offset at its middle frame), eased
/// between stretches; the root offset itself when the input never plants the foot.
std::vector<Vec3> footprint_offsets(const std::vector<bool>& planted, const std::vector<Vec3>& root_offset) {
  const int n = static_cast<int>(planted.size());
  struct Stretch {
    int first, last;
    Vec3 offset;
  };
  std::vector<Stretch> stretches;
  for (int f = 0; f < n;) {
    if (!planted[f]) {
      ++f;
      continue;
    }
    int g = f;
    while (g + 1 < n && planted[g + 1]) ++g;
    stretches.push_back({f, g, root_offset[(f + g) / 2]});
    f = g + 1;
  }
  if (stretches.empty()) return root_offset;
  std::vector<Vec3> offsets(n);
  for (int f = 0; f <= stretches.front().last; ++f) offsets[f] = stretches.front().offset;
  for (size_t s = 0; s + 1 < stretches.size(); ++s) {
    const Stretch& a = stretches[s];
    const Stretch& b = stretches[s + 1];
    const int gap = b.first - a.last;
    for (int f = a.last + 1; f < b.first; ++f) {
      const double w = raised_cosine(f - a.last, gap);
      offsets[f] = (1.0 - w) * a.offset + w * b.offset;
    }
    for (int f = b.first; f <= b.last; ++f) offsets[f] = b.offset;
  }
  for (int f = stretches.back().last + 1; f < n; ++f) offsets[f] = stretches.back().offset;
  return offsets;
}

bool all_zero(const std::vector<Vec3>& v) {
  return std::all_of(v.begin(), v.end(), [](const Vec3& x) { return x.squaredNorm() == 0.0; });
}

void follow_character(const CharacterAnimation& in, const CharacterAnimation& out, double fps,
                      const FollowRootDef& def, const CorrectorParams& plant_test,
                      CharacterAnimation& result) {
  std::vector<Vec3> root_offset = smoothed_root_offsets(in, out, def.smoothing_s * fps);
  for (Vec3& offset : root_offset) offset *= def.share;
  if (all_zero(root_offset)) return;
  std::vector<BoneTransforms> bones(in.frames.size());
  for (size_t f = 0; f < in.frames.size(); ++f) bones[f] = forward_kinematics(in.shape, in.frames[f]);
  for (size_t f = 0; f < in.frames.size(); ++f) result.frames[f].root_position_m += root_offset[f];
  const std::array<std::vector<bool>, 2> planted = planted_frames(in, fps, plant_test);
  for (size_t s = 0; s < 2; ++s) {
    const LegJoints leg = leg_joints(kLegSides[s]);
    const std::vector<Vec3> foot_offset = footprint_offsets(planted[s], root_offset);
    for (size_t f = 0; f < in.frames.size(); ++f) {
      const RigidTransform& ankle = bones[f][static_cast<size_t>(leg.ankle)];
      reach_ankle(in.shape, result.frames[f], kLegSides[s], ankle.translation + foot_offset[f],
                  ankle.rotation);
    }
  }
}

}  // namespace

CrowdAnimation follow_root_offsets(const CrowdAnimation& input, const CrowdAnimation& corrected,
                                   const FollowRootDef& def, const CorrectorParams& plant_test) {
  CrowdAnimation result = input;
  for (size_t c = 0; c < input.characters.size(); ++c)
    follow_character(input.characters[c], corrected.characters[c], input.meta.fps, def, plant_test,
                     result.characters[c]);
  return result;
}

}  // namespace crowdlab
