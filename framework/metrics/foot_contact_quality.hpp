#pragma once
// How a corrected crowd animation treats the feet the input plants (issue 18). Every measure compares
// the corrected animation with its input, foot joint by foot joint (ankles and balls, SMPL joints 7, 8,
// 10, 11), frame by frame.
//
// Contact (stance) is detected on the INPUT only: a foot joint is in contact on frame f when it moved
// less than kContactSpeed_mps * dt since frame f-1 and is below kContactHeight_m. This is the usual
// joint height + speed test for foot contact (Ikemoto, Arikan & Forsyth 2006, "Knowing when to put
// your foot down", I3D; Kovar, Schreiner & Gleicher 2002, "Footskate cleanup for motion capture
// editing", SCA, use the same two cues). 0.03 m/s is 1 mm per frame at 30 fps; 15 cm lies above an
// adult ankle joint (~8-10 cm) and below any swing-phase foot. The solver's foot holds use the same
// thresholds (CorrectorParams::foot_plant_speed_mps / foot_plant_height_m), so the measure asks exactly
// whether what the input plants stays planted.
//
//   stance_drift_p99_m, _max_m   per contact frame, the corrected joint's horizontal distance from
//                                where it was on the frame before the contact run began (the landing
//                                point); 99th percentile (nearest rank) and maximum over all contact
//                                frames of all foot joints
//   foot_pops                    foot-joint frames whose corrected displacement since the previous
//                                frame exceeds the input's displacement for that joint and frame by
//                                more than kPopExcess_m = 5 cm (a foot jumping in one frame)
//   pop_excess_max_m             the largest such excess (any frame, also below the threshold)
//   pop_frames                   the frames on which some foot joint popped
//   pop_worst_*                  character, foot joint and frame of pop_excess_max_m (-1: none)
//   ground_penetration_max_m     ABSOLUTE: deepest any foot capsule (ankle and ball bones) goes below
//                                y = 0, per foot and frame (the input's own depth included)
//   (every sole height here, for this and the measures below, is the foot capsules' lowest point plus
//   how far they reach below the rendered mesh's floor in the rest pose: a capsule fitted around a shoe
//   reaches below the sole, and that part is proxy; 0 without a mesh or for capsules above the floor;
//   session 25. So an input and an output with other capsules compare the same soles.)
//   ground_penetration_p99_m     99th percentile of the positive per-foot per-frame depths
//   ground_penetration_added_max_m   ADDED by the correction: per foot and frame, how far the
//                                corrected sole is below min(0, the input's sole at that frame), the
//                                depth below the ground that the input does not have itself; maximum
//                                over all feet and frames (issue 27, session 16: the corridor clips'
//                                input feet are 13.5-14.1 mm below y = 0, and a free foot returns to
//                                its input, so the absolute measure cannot reach 0 there)
//   ground_penetration_added_p99_m   99th percentile of the positive per-foot per-frame added depths
//   ground_added_worst_*         character, ankle (the foot's side) and frame of
//                                ground_penetration_added_max_m (-1: none), to look at it
//   float_p99_m, float_max_m     per contact frame of a foot (either of its joints in contact), how much
//                                higher the corrected sole (lowest point of the foot capsules) is than
//                                the input's; 99th percentile and maximum
#include <vector>

#include "framework/core/crowd_animation.hpp"

namespace crowdlab {

inline constexpr double kContactSpeed_mps = 0.03;
inline constexpr double kContactHeight_m = 0.15;
inline constexpr double kPopExcess_m = 0.05;

struct FootContactQuality {
  double stance_drift_p99_m = 0.0;
  double stance_drift_max_m = 0.0;
  long contact_frames = 0;  ///< foot-joint frames in contact in the input
  int foot_pops = 0;
  std::vector<int> pop_frames;  ///< the frames with a pop, ascending, each once (to look at them)
  double pop_excess_max_m = 0.0;
  int pop_worst_character = -1, pop_worst_joint = -1, pop_worst_frame = -1;
  double ground_penetration_max_m = 0.0;
  double ground_penetration_p99_m = 0.0;
  double ground_penetration_added_max_m = 0.0;
  double ground_penetration_added_p99_m = 0.0;
  int ground_added_worst_character = -1, ground_added_worst_joint = -1, ground_added_worst_frame = -1;
  double float_p99_m = 0.0;
  double float_max_m = 0.0;
};

/// Frames from first_frame on (0 = all). The two animations must match in characters and frames
/// (the caller checks; see measure_correction_quality).
FootContactQuality measure_foot_contact_quality(const CrowdAnimation& input, const CrowdAnimation& corrected,
                                                int first_frame = 0);

}  // namespace crowdlab
