#include "experiments/cli/correction_quality_json.hpp"

namespace crowdlab::cli {

nlohmann::json correction_quality_json(const CorrectionQuality& q) {
  const FootContactQuality& f = q.feet;
  return {{"depth_p99_m", q.depth_p99_m},
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
          {"foot_ground_penetration_max_m", f.ground_penetration_max_m},
          {"foot_ground_penetration_p99_m", f.ground_penetration_p99_m},
          {"foot_float_p99_m", f.float_p99_m},
          {"foot_float_max_m", f.float_max_m}};
}

}  // namespace crowdlab::cli
