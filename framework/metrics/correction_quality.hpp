#pragma once
// How faithfully a corrected crowd animation keeps its input while removing interpenetration: the
// quality targets of the collision correction (issue 5; seed 000 §4.2), measured on the capsule
// bodies independently of the solver's own contact lists.
//
//   depth_p99_m, depth_max_m   99th percentile / maximum of every positive inter-body capsule-capsule
//                              penetration depth r_a + r_b - axis distance (m), over all frames
//   rotation_dev_mean_deg      mean over characters, frames and the 24 joints of the angle between the
//   rotation_dev_p99_deg       input and corrected local rotations (degrees); and its 99th percentile
//   foot_skate_max_m           largest horizontal slide (m) of a foot joint while the input holds it
//                              planted: feet.stance_drift_max_m (kept under its old name for the csv)
//   feet                       stance-foot drift, foot pops, ground penetration and floating of the
//                              feet (foot_contact_quality.hpp, where the contact rule is defined)
//   joint_speed_max_mps        largest joint speed of the corrected animation (m/s, finite differences)
//   free_limbs                 deviation of joints whose limbs touch nobody (issue 27;
//                              free_limb_deviation.hpp)
//   flips                      joint-frames whose deviation from the input jumps (issue 27;
//   core/joint_flips.hpp) environment                capsule depth behind walls, barriers and the stage, of
//   the corrected
//                              animation (issue 27; environment_penetration.hpp)
//   mesh_overlap               rendered-mesh vertices inside another character's rendered mesh, of the
//                              corrected animation (issue 27; mesh_overlap.hpp; sampled every 0.5 s)
//   proxy_coverage             rendered-mesh vertices outside the character's own capsules (issue 27;
//                              proxy_coverage.hpp; sampled every 0.5 s)
// Frames are taken from first_frame on (0 = all), every `frame_stride`-th for the depths. With
// `mesh_measures` false the two mesh-level measures are left empty (frames 0): they cost about three
// quarters of the whole on MPFB2 crowds (closest-point queries against every neighbour's posed mesh), and
// a caller that reads none of them (`reproduce gomez2024 --quick`, issue 31) skips them. `looped`: the
// clip plays as a loop (protocol.loop_video), so the free-limb and flip windows wrap around its end.
#include "framework/core/crowd_animation.hpp"
#include "framework/core/joint_flips.hpp"
#include "framework/core/rotation_angle.hpp"
#include "framework/metrics/environment_penetration.hpp"
#include "framework/metrics/foot_contact_quality.hpp"
#include "framework/metrics/free_limb_deviation.hpp"
#include "framework/metrics/mesh_overlap.hpp"
#include "framework/metrics/proxy_coverage.hpp"

namespace crowdlab {

struct CorrectionQuality {
  double depth_p99_m = 0.0;
  double depth_max_m = 0.0;
  long depth_samples = 0;  ///< number of positive capsule-pair depths seen
  double rotation_dev_mean_deg = 0.0;
  double rotation_dev_p99_deg = 0.0;
  double foot_skate_max_m = 0.0;
  double joint_speed_max_mps = 0.0;
  FootContactQuality feet;
  FreeLimbDeviation free_limbs;
  JointFlips flips;
  EnvironmentPenetration environment;
  MeshOverlap mesh_overlap;
  ProxyCoverage proxy_coverage;
};

/// Throws InputError when the two animations differ in characters or frames.
CorrectionQuality measure_correction_quality(const CrowdAnimation& input, const CrowdAnimation& corrected,
                                             int first_frame = 0, int frame_stride = 1,
                                             bool mesh_measures = true, bool looped = false);

/// The q-quantile (0..1) of v by nearest rank (0 for an empty vector).
double nearest_rank_quantile(std::vector<double> v, double q);

}  // namespace crowdlab
