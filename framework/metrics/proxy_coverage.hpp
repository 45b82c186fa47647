#pragma once
// Proxy coverage (issue 27): whether the collision proxies (one capsule per bone, seed 000 §3.4) bound
// what is rendered. For every rendered-mesh vertex v of a character (posed_meshes.hpp: skin, garments,
// hair, eyes, shoes) on a sampled frame, its distance outside the character's own capsules,
//   out(v) = max(0, min_j (|v - axis_j| - r_j))     (core/capsule.hpp point_capsule_distance),
// and over all vertex-frames:
//   within_share   share with out(v) <= tolerance_m (5 mm: the target is >= 99 %)
//   outside_p99_m, outside_max_m   nearest-rank p99 and max of out(v)
//   within_share_by_surface        the same share per SurfaceKind (core/skinned_mesh.hpp; -1 where a
//                                  kind has no vertex), which names what sticks out (hair, garments)
// Frames as in mesh_overlap.hpp (sampled, parallel, reduced in frame order).
#include <array>

#include "framework/core/crowd_animation.hpp"
#include "framework/core/forward_kinematics.hpp"

namespace crowdlab {

inline constexpr double kProxyCoverageTolerance_m = 0.005;

struct ProxyCoverage {
  int frames = 0;           ///< sampled frames measured (0: no character has a mesh)
  long vertex_samples = 0;  ///< vertex-frames
  double within_share = 1.0;
  double outside_p99_m = 0.0;
  double outside_max_m = 0.0;
  int worst_character = -1, worst_frame = -1;  ///< where outside_max_m is (-1: none)
  std::array<double, static_cast<size_t>(SurfaceKind::kCount)> within_share_by_surface{};
};

/// Distance (m) of p outside the nearest of the capsules (0 inside any of them).
double outside_capsules_m(const Vec3& p, const WorldCapsules& capsules);

/// Frames from first_frame on, one every interval_s seconds.
ProxyCoverage measure_proxy_coverage(const CrowdAnimation& crowd, int first_frame = 0,
                                     double interval_s = 0.5, double tolerance_m = kProxyCoverageTolerance_m);

}  // namespace crowdlab
