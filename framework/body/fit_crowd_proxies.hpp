#pragma once
// The collision proxies of a whole crowd (issue 27): the volume-fitted capsules every body is built with,
// or capsules fitted to each character's rendered mesh (cover_capsules.hpp), so that what the correction
// separates and the capsule metrics measure bounds what is drawn. Used by `crowdlab run`'s animation stage
// (animation.collision_proxies), `crowdlab correct` and `crowdlab experiment overlap-vs-density`.
//   crowd  in/out: every character that carries a rendered mesh gets its capsules fitted as `fit` says
//          (nothing for ProxyFit::volume); characters without a mesh (procedural bodies) keep theirs.
//          Poses are untouched: only BodyShape::capsules change.
// Logs the mean share of rest-pose vertices within 5 mm of the capsules before and after.
#include "framework/core/crowd_animation.hpp"
#include "framework/core/joint_scope.hpp"

namespace crowdlab {

enum class ProxyFit {
  volume,       ///< the body's own capsules, fitted to the volume of the skin each bone carries
  cover_mesh,   ///< grown until every rendered surface lies within 5 mm (`correct --cover-mesh`)
  per_surface,  ///< fitted per surface, axes moved (SurfaceTolerances::per_surface; `--fit-proxies`)
  /// per_surface for the upper body only (kUpperBodyProxies: chest, neck, head, collars, arms); the pelvis,
  /// lower spine and legs keep their volume capsules (`--fit-upper-proxies`; session 26: walking crowds,
  /// whose visible overlap is mostly arms against neighbours' chests, break down with fitted legs and hips)
  upper_body,
};

/// The bones ProxyFit::upper_body fits: spine3 and every bone it carries (neck, head, collars, shoulders,
/// elbows, wrists, hands).
inline constexpr BoneMask kUpperBodyProxies = subtree_mask(kSpine3);

void fit_crowd_proxies(CrowdAnimation& crowd, ProxyFit fit);

}  // namespace crowdlab
