#include "framework/metrics/measure_crowd.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <map>
#include <utility>

#include "framework/core/forward_kinematics.hpp"
#include "framework/metrics/character_overlap.hpp"
#include "framework/metrics/volume_index.hpp"

namespace crowdlab {
namespace {

struct PairSample {
  int a = 0;
  int b = 0;
  double volume_m3 = 0.0;
  double depth_m = 0.0;
};

/// Everything measured on one frame (written to its own slot, reduced later in frame order).
struct FrameSample {
  std::vector<double> character_overlap_m3;
  std::vector<PairSample> pairs;  ///< colliding pairs, ordered by (a, b)
  double max_error_bound_m3 = 0.0;
};

FrameSample measure_frame(const CrowdAnimation& crowd, int f, const MetricsOptions& options) {
  const size_t n = crowd.characters.size();
  std::vector<WorldCapsules> bodies(n);
  std::vector<Aabb> bounds(n);
  for (size_t i = 0; i < n; ++i) {
    const CharacterAnimation& c = crowd.characters[i];
    bodies[i] = world_capsules(c.shape, c.frames[static_cast<size_t>(f)]);
    bounds[i] = capsules_box(bodies[i]);
  }
  FrameSample out;
  out.character_overlap_m3.assign(n, 0.0);
  for (size_t i = 0; i < n; ++i) {
    const OverlapVolume v = overlap_with_others(bodies, bounds, static_cast<int>(i), options.overlap);
    out.character_overlap_m3[i] = v.volume_m3;
    out.max_error_bound_m3 = std::max(out.max_error_bound_m3, v.error_bound_m3());
  }
  for (size_t i = 0; i < n; ++i) {
    for (size_t j = i + 1; j < n; ++j) {
      if (!bounds[i].overlaps(bounds[j])) continue;
      const double depth = max_penetration_depth(bodies[i], bodies[j]);
      if (depth <= 0.0) continue;
      PairSample s{static_cast<int>(i), static_cast<int>(j), 0.0, depth};
      if (options.pair_volumes) {
        const OverlapVolume v = character_overlap(bodies[i], bodies[j], options.overlap);
        s.volume_m3 = v.volume_m3;
        out.max_error_bound_m3 = std::max(out.max_error_bound_m3, v.error_bound_m3());
      }
      out.pairs.push_back(s);
    }
  }
  return out;
}

struct PairTrack {
  std::vector<double> volumes_m3;  ///< one per colliding frame
  int last_frame = -2;
  PairMetrics metrics;
};

}  // namespace

CrowdMetrics measure_crowd(const CrowdAnimation& crowd, const MetricsOptions& options) {
  validate_crowd(crowd, "measure_crowd");
  const int frames = crowd.frame_count();
  const size_t n = crowd.characters.size();
  std::vector<FrameSample> samples(static_cast<size_t>(frames));
  tbb::parallel_for(0, frames,
                    [&](int f) { samples[static_cast<size_t>(f)] = measure_frame(crowd, f, options); });

  CrowdMetrics m;
  m.characters = static_cast<int>(n);
  m.frames = frames;
  m.fps = crowd.meta.fps;
  m.per_frame.resize(static_cast<size_t>(frames));
  m.character_mean_overlap_m3.assign(n, 0.0);
  std::vector<double> total_per_frame(static_cast<size_t>(frames), 0.0);
  std::map<std::pair<int, int>, PairTrack> tracks;
  double overlap_sum = 0.0;
  for (int f = 0; f < frames; ++f) {
    const FrameSample& s = samples[static_cast<size_t>(f)];
    FrameMetrics& fm = m.per_frame[static_cast<size_t>(f)];
    double frame_sum = 0.0;
    for (size_t i = 0; i < n; ++i) {
      frame_sum += s.character_overlap_m3[i];
      m.character_mean_overlap_m3[i] += s.character_overlap_m3[i];
    }
    overlap_sum += frame_sum;
    fm.mean_character_overlap_m3 = n > 0 ? frame_sum / static_cast<double>(n) : 0.0;
    fm.colliding_pairs = static_cast<int>(s.pairs.size());
    for (const PairSample& p : s.pairs) {
      fm.total_pair_overlap_m3 += p.volume_m3;
      fm.max_penetration_depth_m = std::max(fm.max_penetration_depth_m, p.depth_m);
      PairTrack& t = tracks[{p.a, p.b}];
      t.metrics.a = p.a;
      t.metrics.b = p.b;
      if (t.last_frame != f - 1) ++t.metrics.collision_events;
      t.last_frame = f;
      ++t.metrics.colliding_frames;
      t.metrics.max_volume_m3 = std::max(t.metrics.max_volume_m3, p.volume_m3);
      t.metrics.max_penetration_depth_m = std::max(t.metrics.max_penetration_depth_m, p.depth_m);
      t.volumes_m3.push_back(p.volume_m3);
    }
    total_per_frame[static_cast<size_t>(f)] = fm.total_pair_overlap_m3;
    m.max_penetration_depth_m = std::max(m.max_penetration_depth_m, fm.max_penetration_depth_m);
    if (fm.colliding_pairs > 0) ++m.colliding_frames;
    m.max_error_bound_m3 = std::max(m.max_error_bound_m3, s.max_error_bound_m3);
  }
  if (frames > 0) {
    for (double& v : m.character_mean_overlap_m3) v /= frames;
    m.mean_character_overlap_l = 1000.0 * overlap_sum / (static_cast<double>(n) * frames);
  }
  m.volume_index_m = mean_cube_root_volume(total_per_frame);
  for (auto& [key, t] : tracks) {
    t.metrics.volume_index_m = mean_cube_root_volume(t.volumes_m3);
    m.collision_count += t.metrics.collision_events;
    m.pairs.push_back(t.metrics);
  }
  return m;
}

}  // namespace crowdlab
