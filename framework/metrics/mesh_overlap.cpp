#include "framework/metrics/mesh_overlap.hpp"

#include <algorithm>

#include <tbb/parallel_for.h>

#include "framework/metrics/correction_quality.hpp"
#include "framework/metrics/surfaces_inside.hpp"

namespace crowdlab {
namespace {

struct FrameOverlap {
  long vertices = 0;
  std::vector<double> depths;  ///< of the inside vertices
  double max_depth = 0.0;
  int worst_character = -1, worst_other = -1;
};

FrameOverlap frame_overlap(const CrowdAnimation& crowd, int f, double max_depth_m) {
  const FrameSurfaces surfaces(crowd, f);
  FrameOverlap out;
  for (const PosedMesh& ma : surfaces.meshes()) {
    out.vertices += static_cast<long>(ma.vertices.size());
    std::vector<double> depth(ma.vertices.size(), 0.0);
    std::vector<int> by(ma.vertices.size(), -1);
    for (size_t v = 0; v < ma.vertices.size(); ++v)
      depth[v] = surfaces.inside_depth(ma.vertices[v], ma.character, max_depth_m, &by[v]);
    for (size_t v = 0; v < depth.size(); ++v) {
      if (by[v] < 0) continue;
      out.depths.push_back(depth[v]);
      if (depth[v] > out.max_depth) {
        out.max_depth = depth[v];
        out.worst_character = ma.character;
        out.worst_other = by[v];
      }
    }
  }
  return out;
}

}  // namespace

MeshOverlap measure_mesh_overlap(const CrowdAnimation& crowd, int first_frame, double interval_s,
                                 double max_depth_m) {
  MeshOverlap q;
  const bool any_mesh = std::any_of(crowd.characters.begin(), crowd.characters.end(),
                                    [](const auto& c) { return c.mesh != nullptr; });
  if (!any_mesh) return q;
  q.sampled_frames = mesh_sample_frames(crowd, first_frame, interval_s);
  std::vector<FrameOverlap> per(q.sampled_frames.size());
  tbb::parallel_for(size_t{0}, per.size(),
                    [&](size_t i) { per[i] = frame_overlap(crowd, q.sampled_frames[i], max_depth_m); });
  std::vector<double> depths;
  for (size_t i = 0; i < per.size(); ++i) {
    const FrameOverlap& fo = per[i];
    const double fraction =
        fo.vertices > 0 ? static_cast<double>(fo.depths.size()) / static_cast<double>(fo.vertices) : 0.0;
    q.per_frame_fraction.push_back(fraction);
    q.fraction_mean += fraction;
    q.fraction_max = std::max(q.fraction_max, fraction);
    depths.insert(depths.end(), fo.depths.begin(), fo.depths.end());
    if (fo.max_depth > q.depth_max_m) {
      q.depth_max_m = fo.max_depth;
      q.worst_character = fo.worst_character;
      q.worst_other = fo.worst_other;
      q.worst_frame = q.sampled_frames[i];
    }
  }
  q.frames = static_cast<int>(per.size());
  if (q.frames > 0) q.fraction_mean /= q.frames;
  q.inside_samples = static_cast<long>(depths.size());
  q.depth_p99_m = nearest_rank_quantile(std::move(depths), 0.99);
  return q;
}

}  // namespace crowdlab
