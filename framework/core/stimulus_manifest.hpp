#pragma once
// StimulusManifest: what the stimuli stage produced, as the study and analysis stages read it.
// Stored as DIR/manifest.csv with columns:
//   id,<factor columns...>,file,duration_s,frames,width,height,sha256,overlap_l,v_i_m,collisions,practice,
//   depth_p99_m,depth_max_m,stance_foot_drift_p99_m,stance_foot_drift_max_m,foot_pops,
//   foot_ground_penetration_max_m,foot_ground_penetration_added_max_m,foot_float_p99_m,free_limb_dev_p99_deg,
//   free_limb_dev_max_deg,
//   joint_flips,env_penetration_p99_m,env_penetration_max_m,mesh_overlap_fraction,
//   mesh_overlap_depth_p99_m,proxy_coverage,proxy_outside_p99_m,crowd_in_frame_min,character_height_px,
//   overlap_frame_share,overlap_pixel_fraction,seam_step_ratio
// (factor columns in spec order; metric columns empty when not computed). Eight of them are the
// correction-quality measures of the clip's crowd against its input (issue 18, and issue 27's ground
// penetration added by the correction; definitions in
// framework/metrics/correction_quality.hpp and foot_contact_quality.hpp, names as in
// correction_quality.csv): for `baseline` the input is the crowd itself, for `ours` the baseline of the
// same condition; the next five (issue 27) are defined in framework/metrics/free_limb_deviation.hpp,
// framework/core/joint_flips.hpp and framework/metrics/environment_penetration.hpp; the four after them
// (issue 27, the rendered meshes: empty for bodies without one) in framework/metrics/mesh_overlap.hpp and
// proxy_coverage.hpp. The last five are the stimulus check of the rendered clip (issue 28; definitions in
// stimuli/stimulus_check.hpp), also in the clip's sidecar JSON. Manifests written before any group lack its
// columns and read as unknown.
#include <map>
#include <string>
#include <vector>

namespace crowdlab {

/// The correction-quality measures of one clip's crowd against its input (see the header); metres,
/// -1 = unknown.
struct ClipQuality {
  double depth_p99_m = -1.0;                    ///< p99 inter-body capsule depth
  double depth_max_m = -1.0;                    ///< largest inter-body capsule depth
  double stance_foot_drift_p99_m = -1.0;        ///< horizontal slide of planted foot joints, p99
  double stance_foot_drift_max_m = -1.0;        ///< and max
  int foot_pops = -1;                           ///< foot-joint frames moving > 5 cm more than the input's
  double foot_ground_penetration_max_m = -1.0;  ///< deepest a foot goes below y = 0 (empty on surfaces)
  double foot_float_p99_m = -1.0;               ///< planted feet higher than the input's, p99
  double free_limb_dev_p99_deg = -1.0;          ///< deviation of joints touching nobody, p99 (degrees)
  double free_limb_dev_max_deg = -1.0;          ///< and max
  int joint_flips = -1;                         ///< joint-frames whose deviation jumps > 200 deg/s over 0.1 s
  double env_penetration_p99_m = -1.0;          ///< capsule depth behind walls / barriers / stage, p99
  double env_penetration_max_m = -1.0;          ///< and max
  double mesh_overlap_fraction = -1.0;          ///< rendered vertices inside another character, mean share
  double mesh_overlap_depth_p99_m = -1.0;       ///< their depth, p99
  double proxy_coverage = -1.0;                 ///< rendered vertices within 5 mm of their own capsules
  double proxy_outside_p99_m = -1.0;            ///< distance outside the capsules, p99
  /// Deepest a foot goes below min(0, its input's height): what the correction adds (empty on surfaces).
  double foot_ground_penetration_added_max_m = -1.0;
};

/// The stimulus check of one rendered clip (stimuli/stimulus_check.hpp defines the measures); -1 = unknown.
struct StimulusCheck {
  double crowd_in_frame_min = -1.0;      ///< share of characters wholly inside the image, min over frames
  double character_height_px = -1.0;     ///< median on-screen character height, pixels
  double overlap_frame_share = -1.0;     ///< share of sampled frames with overlap pixels (overlap mode)
  double overlap_pixel_fraction = -1.0;  ///< mean share of the image's pixels that show overlap
  double seam_step_ratio = -1.0;         ///< last-to-first frame step / median frame step
};

struct StimulusEntry {
  std::string id;                              ///< condition id (+ "_" + viewpoint when rendered per view)
  std::map<std::string, std::string> factors;  ///< factor name -> level text
  std::string file;                            ///< path relative to the manifest's folder
  double duration_s = 0.0;
  int frames = 0;
  int width = 0;
  int height = 0;
  std::string sha256;
  double mean_overlap_l = -1.0;  ///< per-character mean overlap volume, litres (-1 = unknown)
  double v_i_m = -1.0;           ///< seed 001 Eq. 1, metres (-1 = unknown)
  int collisions = -1;           ///< colliding character pairs over the clip (-1 = unknown)
  bool practice = false;
  ClipQuality quality;
  StimulusCheck check;
};

struct StimulusManifest {
  std::vector<std::string> factor_names;  ///< column order
  std::vector<StimulusEntry> entries;
};

/// Writes / reads DIR/manifest.csv. read_manifest() throws InputError naming file, row and column.
void write_manifest(const StimulusManifest& manifest, const std::string& csv_path);
StimulusManifest read_manifest(const std::string& csv_path);

}  // namespace crowdlab
