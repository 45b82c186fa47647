#pragma once
// Proxies that bound what is rendered (issue 27): grows a body's bone capsules (seed 000 §3.4) until its
// rendered mesh (skin, garments, hair, shoes, eyes: core/skinned_mesh.hpp) lies within a tolerance of them
// in the rest pose. make_mpfb2_body() fits each radius to the volume of the skin its bone carries, so
// about half of the skin lies outside the capsules (by up to a few cm) and garments and hair more.
//
// For every rest-pose vertex v, the capsule it is nearest the surface of, j*(v) = argmin_j (|v - axis_j|
// - r_j), is the one that has to take it in (the least growth); then
//   r_j <- max(r_j, max over v with j*(v) = j of |v - axis_j| - tolerance)
// (the axes stay). One pass suffices: growing a radius only brings vertices closer. The rest-contact
// pairs (self-collision exclusions) are recomputed. Posed, linear-blend skinning bends the mesh at the
// joints where the rigid capsules do not, so coverage in motion is measured separately
// (metrics/proxy_coverage.hpp).
#include <array>

#include "framework/core/body_shape.hpp"
#include "framework/core/skinned_mesh.hpp"

namespace crowdlab {

struct CoverReport {
  double within_before = 0.0;  ///< share of rest vertices within tolerance of the capsules, before
  double within_after = 0.0;   ///< and after (1 by construction, up to round-off)
  std::array<double, kJointCount> growth_m{};  ///< radius added per bone (m)
};

/// Grows shape's capsule radii so that mesh (in the rest pose of `shape`) lies within tolerance_m of
/// them; returns the shares before and after and the growth per bone.
CoverReport cover_mesh_with_capsules(BodyShape& shape, const SkinnedMesh& mesh, double tolerance_m = 0.005);

}  // namespace crowdlab
