#pragma once
// Every interpenetration measure of a crowd animation, frame by frame, on the capsule bodies.
//
// Per frame f:
//   mean_character_overlap_m3  mean over characters i of v_i(f) = vol(body_i ∩ ∪_{j≠i} body_j)
//                              (seed 000 Figure 3: each character's overlap with all others)
//   total_pair_overlap_m3      sum over character pairs of vol(body_i ∩ body_j)
//   max_penetration_depth_m    max over inter-body capsule pairs of r_a + r_b - axis distance (>= 0)
//   colliding_pairs            character pairs with a capsule pair at depth > 0
// Whole clip:
//   mean_character_overlap_l   mean of v_i(f) over characters and frames, in litres (Figure 3's y axis)
//   volume_index_m             V of seed 001 Eq. 1 on v(f) = total_pair_overlap_m3 (for a two-character
//                              clip this is exactly the paper's V_i); per pair in `pairs`
//   collision_count            collision events: a character pair that overlaps at frame f and did not
//                              at f - 1 (a pair already overlapping at frame 0 counts as one event)
//   max_error_bound_m3         the largest rigorous error bound of any single volume computed
// Frames are measured in parallel (TBB); each frame is computed serially and reduced in frame order,
// so results are bit-identical for any thread count.
#include <functional>
#include <vector>

#include "framework/core/crowd_animation.hpp"
#include "framework/metrics/overlap_volume.hpp"

namespace crowdlab {

struct MetricsOptions {
  OverlapOptions overlap;
  bool pair_volumes = true;  ///< also integrate every colliding pair's own volume (V per pair)
  /// Called once per finished frame, from worker threads (e.g. Progress::advance); may be empty.
  std::function<void()> on_frame_done;
};

struct FrameMetrics {
  double mean_character_overlap_m3 = 0.0;
  double total_pair_overlap_m3 = 0.0;
  double max_penetration_depth_m = 0.0;
  int colliding_pairs = 0;
};

struct PairMetrics {
  int a = 0;  ///< character indices, a < b
  int b = 0;
  int colliding_frames = 0;
  int collision_events = 0;
  double volume_index_m = 0.0;  ///< Eq. 1 over this pair's frames
  double max_volume_m3 = 0.0;
  double max_penetration_depth_m = 0.0;
};

struct CrowdMetrics {
  int characters = 0;
  int frames = 0;
  double fps = 0.0;
  std::vector<FrameMetrics> per_frame;
  std::vector<double> character_mean_overlap_m3;  ///< per character, mean over frames
  std::vector<PairMetrics> pairs;                 ///< pairs that ever collide, ordered by (a, b)
  double mean_character_overlap_l = 0.0;
  double volume_index_m = 0.0;
  double max_penetration_depth_m = 0.0;
  int collision_count = 0;
  int colliding_frames = 0;
  double max_error_bound_m3 = 0.0;
};

/// Throws InputError when the crowd is invalid (see validate_crowd()).
CrowdMetrics measure_crowd(const CrowdAnimation& crowd, const MetricsOptions& options = {});

}  // namespace crowdlab
