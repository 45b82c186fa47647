#include "framework/metrics/proxy_coverage.hpp"

#include <algorithm>

#include <tbb/parallel_for.h>

#include "framework/core/point_capsule_distance.hpp"
#include "framework/metrics/correction_quality.hpp"
#include "framework/metrics/posed_meshes.hpp"

namespace crowdlab {
namespace {

constexpr size_t kKinds = static_cast<size_t>(SurfaceKind::kCount);

struct FrameCoverage {
  std::vector<double> outside;  ///< the positive distances (a clip has millions of vertex-frames, most 0)
  long vertices = 0;
  std::array<long, kKinds> within{}, total{};
  double max_m = 0.0;
  int worst_character = -1;
};

FrameCoverage frame_coverage(const CrowdAnimation& crowd, int f, double tolerance_m) {
  FrameCoverage out;
  for (const PosedMesh& m : posed_meshes(crowd, f)) {
    const CharacterAnimation& ch = crowd.characters[static_cast<size_t>(m.character)];
    const WorldCapsules caps = world_capsules(ch.shape, ch.frames[static_cast<size_t>(f)]);
    for (size_t v = 0; v < m.vertices.size(); ++v) {
      // The vertex's own bones first: most vertices lie inside one of them, and then no other matters.
      double d = 1e300;
      for (int j : ch.mesh->joints[v])
        d = std::min(d, point_capsule_distance(m.vertices[v], caps[static_cast<size_t>(j)]));
      if (d > 0.0) d = outside_capsules_m(m.vertices[v], caps);
      const double o = std::max(0.0, d);
      ++out.vertices;
      if (o > 0.0) out.outside.push_back(o);
      const size_t kind = ch.mesh->surface.empty() ? 0 : std::min<size_t>(ch.mesh->surface[v], kKinds - 1);
      ++out.total[kind];
      if (o <= tolerance_m) ++out.within[kind];
      if (o > out.max_m) {
        out.max_m = o;
        out.worst_character = m.character;
      }
    }
  }
  return out;
}

/// The nearest-rank q-quantile of `zeros` zeros and the positive values `positive`.
double quantile_with_zeros(std::vector<double> positive, long zeros, double q) {
  const long n = zeros + static_cast<long>(positive.size());
  if (n == 0) return 0.0;
  const long k = static_cast<long>(q * static_cast<double>(n - 1) + 0.5);
  if (k < zeros) return 0.0;
  std::sort(positive.begin(), positive.end());
  return positive[static_cast<size_t>(k - zeros)];
}

}  // namespace

double outside_capsules_m(const Vec3& p, const WorldCapsules& capsules) {
  double d = 1e300;
  for (const Capsule& c : capsules) d = std::min(d, point_capsule_distance(p, c));
  return std::max(0.0, d);
}

ProxyCoverage measure_proxy_coverage(const CrowdAnimation& crowd, int first_frame, double interval_s,
                                     double tolerance_m) {
  ProxyCoverage q;
  q.within_share_by_surface.fill(-1.0);
  const bool any_mesh = std::any_of(crowd.characters.begin(), crowd.characters.end(),
                                    [](const auto& c) { return c.mesh != nullptr; });
  if (!any_mesh) return q;
  const std::vector<int> frames = mesh_sample_frames(crowd, first_frame, interval_s);
  std::vector<FrameCoverage> per(frames.size());
  tbb::parallel_for(size_t{0}, per.size(),
                    [&](size_t i) { per[i] = frame_coverage(crowd, frames[i], tolerance_m); });
  std::vector<double> outside;
  long vertices = 0;
  std::array<long, kKinds> within{}, total{};
  for (size_t i = 0; i < per.size(); ++i) {
    outside.insert(outside.end(), per[i].outside.begin(), per[i].outside.end());
    vertices += per[i].vertices;
    for (size_t k = 0; k < kKinds; ++k) {
      within[k] += per[i].within[k];
      total[k] += per[i].total[k];
    }
    if (per[i].max_m > q.outside_max_m) {
      q.outside_max_m = per[i].max_m;
      q.worst_character = per[i].worst_character;
      q.worst_frame = frames[i];
    }
  }
  q.frames = static_cast<int>(frames.size());
  q.vertex_samples = vertices;
  long all_within = 0;
  for (size_t k = 0; k < kKinds; ++k) {
    all_within += within[k];
    if (total[k] > 0)
      q.within_share_by_surface[k] = static_cast<double>(within[k]) / static_cast<double>(total[k]);
  }
  if (q.vertex_samples > 0)
    q.within_share = static_cast<double>(all_within) / static_cast<double>(q.vertex_samples);
  const long zeros = vertices - static_cast<long>(outside.size());
  q.outside_p99_m = quantile_with_zeros(std::move(outside), zeros, 0.99);
  return q;
}

}  // namespace crowdlab
