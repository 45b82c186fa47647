#pragma once
// Overlap between posed characters, with the broad phase of seed 000 §3.4 ("Culling"): body AABBs
// first, then each capsule's bounding sphere against the other body's AABB, then the exact
// capsule-capsule test inside overlap_volume().
//   character_overlap(a, b)       v between two characters (their world capsules, metres)
//   overlap_with_others(bodies, i) v between character i and the union of all other characters:
//                                  vol(body_i ∩ ∪_{j != i} body_j), so a region where three bodies
//                                  meet is counted once for i (seed 000 Figure 3's per-character
//                                  overlap; the paper does not say how triple overlaps count).
//   max_penetration_depth(a, b)   (core/penetration_depth.hpp, included here) the deepest capsule pair.
#include <span>

#include "framework/core/capsule_box.hpp"
#include "framework/core/forward_kinematics.hpp"
#include "framework/core/penetration_depth.hpp"
#include "framework/metrics/overlap_volume.hpp"

namespace crowdlab {

OverlapVolume character_overlap(const WorldCapsules& a, const WorldCapsules& b,
                                const OverlapOptions& options = {});

/// bounds[j] must be capsules_box(bodies[j]); i indexes bodies.
OverlapVolume overlap_with_others(std::span<const WorldCapsules> bodies, std::span<const Aabb> bounds, int i,
                                  const OverlapOptions& options = {});

}  // namespace crowdlab
