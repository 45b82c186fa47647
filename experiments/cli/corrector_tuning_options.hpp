#pragma once
// The corrector's tuning options shared by `crowdlab correct`, `crowdlab bench correct` and `crowdlab
// experiment overlap-vs-density` (defaults = CorrectorParams; units and sources in corrector_params.hpp).
#include <memory>
#include <string>

#include "experiments/cli/command.hpp"
#include "framework/correction/corrector_params.hpp"

namespace crowdlab::cli {

/// Adds --anticipated-joints, --anticipation-rate and --anticipation-runs (offline correction only:
/// framework/correction/anticipate_contacts.hpp).
inline void add_anticipation_options(Command* cmd, CorrectorParams& params) {
  cmd->add_option("--anticipated-joints", params.anticipated_joints,
                  "Joints whose contact deviations are ramped into the targets of another run, so they "
                  "start before a contact instead of within a frame (offline only)")
      ->check(check::is_member({"none", "arms", "upper", "legs", "all"}))
      ->capture_default_str();
  cmd->add_option("--anticipation-rate", params.anticipation_rate_radps, "Rate of those ramps (rad/s)")
      ->check(check::positive_number())
      ->capture_default_str();
  cmd->add_option("--anticipation-runs", params.anticipation_runs,
                  "Runs after the first, each ramping the previous run's deviations")
      ->check(check::range(1, 10))
      ->capture_default_str();
}

/// Adds --contact-stiffness, --cg-tolerance, --active-set-passes, --depenetration-passes,
/// --depenetration-tolerance, --foot-pop-budget, --free-joints, --free-joint-margin, --free-joint-hold,
/// --free-joint-return, --rate-limited-joints, --settle-feet and the anticipation
/// options to `cmd`, writing into `params` (which must outlive the parse).
inline void add_corrector_tuning_options(Command* cmd, CorrectorParams& params) {
  cmd->add_option("--contact-stiffness", params.contact_stiffness, "Collision penalty k_delta (N/m)")
      ->capture_default_str();
  cmd->add_option("--cg-tolerance", params.cg_tolerance, "CG relative residual tolerance")
      ->check(check::range(1e-12, 0.5))
      ->capture_default_str();
  cmd->add_option("--active-set-passes", params.active_set_passes,
                  "Re-solves per step after removing pulling contacts (0 = off)")
      ->capture_default_str();
  cmd->add_option("--depenetration-passes", params.depenetration_passes,
                  "Position-level depenetration passes per step (0 = off)")
      ->check(check::range(0, 100))
      ->capture_default_str();
  cmd->add_option("--depenetration-tolerance", params.depenetration_tolerance_m,
                  "Depth (m) above which the depenetration pass separates a capsule pair")
      ->check(check::range(0.0, 0.1))
      ->capture_default_str();
  cmd->add_option("--foot-pop-budget", params.foot_pop_budget_m,
                  "How much farther than its input a foot joint may move per step in the "
                  "depenetration pass (m, 0 = off)")
      ->check(check::range(0.0, 1.0))
      ->capture_default_str();
  cmd->add_option("--free-joints", params.release_free_joints,
                  "Return joints that touch nobody to their input (true/false; false = the session-8 solver)")
      ->capture_default_str();
  cmd->add_option("--free-joint-margin", params.free_joint_margin_m,
                  "Capsule distance (m) within which a bone counts as in contact for the free-joint release")
      ->check(check::range(0.0, 1.0))
      ->capture_default_str();
  cmd->add_option("--free-joint-hold", params.free_joint_hold_s,
                  "Seconds a joint stays engaged after its last contact")
      ->check(check::range(0.0, 10.0))
      ->capture_default_str();
  cmd->add_option("--free-joint-return", params.free_joint_return_radps,
                  "Rate (rad/s) at which a released joint returns to its input")
      ->check(check::range(0.0, 1000.0))
      ->capture_default_str();
  // The list is bound to a string the option's callback keeps alive, and parsed into the set.
  auto joints = std::make_shared<std::string>(joint_set_name(params.rate_limited_joints));
  cmd->add_option("--rate-limited-joints", *joints,
                  "Joints that turn at most --free-joint-return while in contact: none, or groups (light: "
                  "wrists, hands, ankles, balls; elbows; head: neck, head; shoulders: collars, shoulders; "
                  "spine; hips; knees) and SMPL joint names, comma-separated")
      ->capture_default_str()
      ->each(
          [joints, &params](const std::string& list) { params.rate_limited_joints = parse_joint_set(list); });
  cmd->add_option("--knee-hinge", params.knee_hinge,
                  "Engaged knees keep their flexion and turn off their hinge at most --free-joint-return "
                  "(true/false; false = only their twist limited, the session-15 solver)")
      ->capture_default_str();
  cmd->add_option("--lift-off-knees", params.lift_off_knees,
                  "Engaged knees of legs whose foot is not held return from more than 3 --free-joint-return "
                  "turns off the input at that rate, and a foot held at its ball only pivots about it at 4, "
                  "its knee returning at that rate (true/false)")
      ->capture_default_str();
  cmd->add_option("--held-ankle-twist", params.held_ankle_twist_in_pass,
                  "The depenetration pass turns a held foot's ankle about its up axis at most "
                  "--free-joint-return (true/false)")
      ->capture_default_str();
  cmd->add_option("--settle-feet", params.held_feet_at_input_height,
                  "Hold planted feet at the input's height: held balls at their own, bodies settled onto "
                  "held feet (true/false)")
      ->capture_default_str();
  cmd->add_option("--feet-above-ground", params.feet_above_input_ground,
                  "Lift feet the correction put over 5 mm below the input's ground (min(0, the input's "
                  "sole)) back to 5 mm below it by the leg IK (true/false)")
      ->capture_default_str();
  add_anticipation_options(cmd, params);
}

}  // namespace crowdlab::cli
