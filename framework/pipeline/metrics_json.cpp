#include "framework/pipeline/metrics_json.hpp"

#include <string>

#include "framework/core/skeleton.hpp"
#include "framework/core/surface_kind_name.hpp"

namespace crowdlab {
namespace {

/// {"character", "joint" (SMPL name), "frame"} of a worst case, or null when there is none.
nlohmann::json worst_json(int character, int joint, int frame) {
  if (character < 0) return nullptr;
  return {{"character", character}, {"joint", std::string(joint_name(joint))}, {"frame", frame}};
}

nlohmann::json flips_json(const JointFlips& flips) {
  nlohmann::json list = nlohmann::json::array();
  for (const JointFlip& f : flips.first) {
    nlohmann::json j = worst_json(f.character, f.joint, f.frame);
    j["change_deg"] = f.change_deg;
    list.push_back(std::move(j));
  }
  return list;
}

/// {joint name: flips} for the joints that flipped.
nlohmann::json flips_by_joint_json(const JointFlips& flips) {
  nlohmann::json by = nlohmann::json::object();
  for (int j = 0; j < kJointCount; ++j)
    if (flips.per_joint[static_cast<size_t>(j)] > 0)
      by[std::string(joint_name(j))] = flips.per_joint[static_cast<size_t>(j)];
  return by;
}

/// The mesh-level measures (issue 27), or nothing when no character has a rendered mesh.
void add_mesh_measures(const CorrectionQuality& q, nlohmann::json& j) {
  const MeshOverlap& m = q.mesh_overlap;
  if (m.frames > 0) {
    j["mesh_overlap_frames"] = m.frames;
    j["mesh_overlap_fraction"] = m.fraction_mean;
    j["mesh_overlap_fraction_max"] = m.fraction_max;
    j["mesh_overlap_depth_p99_m"] = m.depth_p99_m;
    j["mesh_overlap_depth_max_m"] = m.depth_max_m;
    j["mesh_overlap_worst"] = m.worst_character < 0 ? nlohmann::json(nullptr)
                                                    : nlohmann::json{{"character", m.worst_character},
                                                                     {"other", m.worst_other},
                                                                     {"frame", m.worst_frame}};
    j["mesh_overlap_per_frame"] = {{"frame", m.sampled_frames}, {"fraction", m.per_frame_fraction}};
  }
  const ProxyCoverage& p = q.proxy_coverage;
  if (p.frames > 0) {
    j["proxy_coverage"] = p.within_share;
    j["proxy_outside_p99_m"] = p.outside_p99_m;
    j["proxy_outside_max_m"] = p.outside_max_m;
    nlohmann::json by = nlohmann::json::object();
    for (size_t k = 0; k < p.within_share_by_surface.size(); ++k)
      if (p.within_share_by_surface[k] >= 0)
        by[std::string(surface_kind_name(static_cast<SurfaceKind>(k)))] = p.within_share_by_surface[k];
    j["proxy_coverage_by_surface"] = by;
  }
}

}  // namespace

nlohmann::json crowd_metrics_json(const CrowdMetrics& m, bool per_frame) {
  nlohmann::json j = {{"characters", m.characters},
                      {"frames", m.frames},
                      {"fps", m.fps},
                      {"mean_character_overlap_l", m.mean_character_overlap_l},
                      {"volume_index_m", m.volume_index_m},
                      {"max_penetration_depth_m", m.max_penetration_depth_m},
                      {"collision_count", m.collision_count},
                      {"colliding_frames", m.colliding_frames},
                      {"max_error_bound_l", 1000.0 * m.max_error_bound_m3}};
  nlohmann::json chars = nlohmann::json::array();
  for (double v : m.character_mean_overlap_m3) chars.push_back(1000.0 * v);
  j["character_mean_overlap_l"] = chars;
  nlohmann::json pairs = nlohmann::json::array();
  for (const PairMetrics& p : m.pairs)
    pairs.push_back({{"a", p.a},
                     {"b", p.b},
                     {"colliding_frames", p.colliding_frames},
                     {"collision_events", p.collision_events},
                     {"volume_index_m", p.volume_index_m},
                     {"max_volume_l", 1000.0 * p.max_volume_m3},
                     {"max_penetration_depth_m", p.max_penetration_depth_m}});
  j["pairs"] = pairs;
  if (per_frame) {
    nlohmann::json mean = nlohmann::json::array(), total = nlohmann::json::array(),
                   depth = nlohmann::json::array(), count = nlohmann::json::array();
    for (const FrameMetrics& f : m.per_frame) {
      mean.push_back(1000.0 * f.mean_character_overlap_m3);
      total.push_back(1000.0 * f.total_pair_overlap_m3);
      depth.push_back(f.max_penetration_depth_m);
      count.push_back(f.colliding_pairs);
    }
    j["per_frame"] = {{"mean_character_overlap_l", mean},
                      {"total_pair_overlap_l", total},
                      {"max_penetration_depth_m", depth},
                      {"colliding_pairs", count}};
  }
  return j;
}

nlohmann::json correction_quality_json(const CorrectionQuality& q) {
  const FootContactQuality& f = q.feet;
  nlohmann::json j = {
      {"depth_p99_m", q.depth_p99_m},
      {"depth_max_m", q.depth_max_m},
      {"rotation_dev_mean_deg", q.rotation_dev_mean_deg},
      {"rotation_dev_p99_deg", q.rotation_dev_p99_deg},
      {"foot_skate_max_m", q.foot_skate_max_m},
      {"joint_speed_max_mps", q.joint_speed_max_mps},
      {"stance_foot_drift_p99_m", f.stance_drift_p99_m},
      {"stance_foot_drift_max_m", f.stance_drift_max_m},
      {"contact_frames", f.contact_frames},
      {"foot_pops", f.foot_pops},
      {"foot_pop_excess_max_m", f.pop_excess_max_m},
      {"foot_pop_frames", f.pop_frames},
      {"foot_pop_worst", worst_json(f.pop_worst_character, f.pop_worst_joint, f.pop_worst_frame)},
      {"foot_ground_penetration_max_m", f.ground_penetration_max_m},
      {"foot_ground_penetration_p99_m", f.ground_penetration_p99_m},
      {"foot_ground_penetration_added_max_m", f.ground_penetration_added_max_m},
      {"foot_ground_penetration_added_p99_m", f.ground_penetration_added_p99_m},
      {"foot_ground_penetration_added_worst",
       worst_json(f.ground_added_worst_character, f.ground_added_worst_joint, f.ground_added_worst_frame)},
      {"foot_float_p99_m", f.float_p99_m},
      {"foot_float_max_m", f.float_max_m},
      {"free_limb_dev_p99_deg", q.free_limbs.p99_deg},
      {"free_limb_dev_max_deg", q.free_limbs.max_deg},
      {"free_limb_joint_frames", q.free_limbs.free_joint_frames},
      {"free_limb_dev_worst",
       worst_json(q.free_limbs.worst_character, q.free_limbs.worst_joint, q.free_limbs.worst_frame)},
      {"joint_flips", q.flips.count},
      {"joint_flip_max_change_deg", q.flips.max_change_deg},
      {"joint_flip_first", flips_json(q.flips)},
      {"joint_flips_by_joint", flips_by_joint_json(q.flips)},
      {"env_penetration_p99_m", q.environment.p99_m},
      {"env_penetration_max_m", q.environment.max_m},
      {"env_penetration_worst",
       worst_json(q.environment.worst_character, q.environment.worst_bone, q.environment.worst_frame)}};
  add_mesh_measures(q, j);
  return j;
}

}  // namespace crowdlab
