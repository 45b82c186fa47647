#include "framework/metrics/correction_quality.hpp"

#include <algorithm>
#include <cmath>

#include "framework/core/error.hpp"
#include "framework/core/forward_kinematics.hpp"
#include "framework/metrics/character_overlap.hpp"

namespace crowdlab {

double nearest_rank_quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const auto k = std::min(v.size() - 1, static_cast<size_t>(q * static_cast<double>(v.size() - 1) + 0.5));
  return v[k];
}

CorrectionQuality measure_correction_quality(const CrowdAnimation& input, const CrowdAnimation& corrected,
                                             int first_frame, int frame_stride, bool mesh_measures,
                                             bool looped) {
  if (input.characters.size() != corrected.characters.size() ||
      input.frame_count() != corrected.frame_count())
    throw InputError("correction quality: input and corrected animations differ in size");
  if (frame_stride < 1) throw InputError("correction quality: frame_stride must be >= 1");
  CorrectionQuality q;
  const int frames = input.frame_count();
  const size_t n = input.characters.size();
  const double fps = input.meta.fps;

  std::vector<double> depths, deviations;
  for (int f = std::max(0, first_frame); f < frames; f += frame_stride) {
    std::vector<WorldCapsules> bodies;
    std::vector<Aabb> bounds;
    for (const CharacterAnimation& ch : corrected.characters) {
      bodies.push_back(world_capsules(ch.shape, ch.frames[static_cast<size_t>(f)]));
      bounds.push_back(capsules_box(bodies.back()));
    }
    for (size_t i = 0; i < n; ++i)
      for (size_t j = i + 1; j < n; ++j) {
        if (!bounds[i].overlaps(bounds[j])) continue;
        for (const Capsule& a : bodies[i])
          for (const Capsule& b : bodies[j]) {
            const double d = capsule_contact(a, b).depth_m;
            if (d > 0.0) depths.push_back(d);
          }
      }
  }
  q.depth_samples = static_cast<long>(depths.size());
  q.depth_p99_m = nearest_rank_quantile(depths, 0.99);
  q.depth_max_m = depths.empty() ? 0.0 : *std::max_element(depths.begin(), depths.end());

  double sum = 0.0;
  for (size_t c = 0; c < n; ++c) {
    const CharacterAnimation& in = input.characters[c];
    const CharacterAnimation& out = corrected.characters[c];
    for (int f = std::max(0, first_frame); f < frames; ++f)
      for (size_t j = 0; j < kJointCount; ++j) {
        const double a = rotation_angle_deg(in.frames[static_cast<size_t>(f)].local_rotations[j],
                                            out.frames[static_cast<size_t>(f)].local_rotations[j]);
        deviations.push_back(a);
        sum += a;
      }
    // Joint speed needs consecutive frames.
    std::array<Vec3, kJointCount> prev_out;
    prev_out.fill(Vec3::Zero());
    for (int f = std::max(0, first_frame); f < frames; ++f) {
      const auto pout = joint_positions(out.shape, out.frames[static_cast<size_t>(f)]);
      if (f > std::max(0, first_frame))
        for (size_t j = 0; j < kJointCount; ++j)
          q.joint_speed_max_mps = std::max(q.joint_speed_max_mps, (pout[j] - prev_out[j]).norm() * fps);
      prev_out = pout;
    }
  }
  q.feet = measure_foot_contact_quality(input, corrected, first_frame);
  q.free_limbs = measure_free_limb_deviation(input, corrected, first_frame, looped);
  q.flips = measure_joint_flips(input, corrected, first_frame, looped);
  q.environment = measure_environment_penetration(corrected, first_frame);
  if (mesh_measures) {
    q.mesh_overlap = measure_mesh_overlap(corrected, first_frame);
    q.proxy_coverage = measure_proxy_coverage(corrected, first_frame);
  }
  q.foot_skate_max_m = q.feet.stance_drift_max_m;
  q.rotation_dev_mean_deg = deviations.empty() ? 0.0 : sum / static_cast<double>(deviations.size());
  q.rotation_dev_p99_deg = nearest_rank_quantile(deviations, 0.99);
  return q;
}

}  // namespace crowdlab
