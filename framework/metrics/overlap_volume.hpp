#pragma once
// Volume of overlap between two capsule bodies: v = vol((union of A's capsules) ∩ (union of B's)).
//
// This is the interpenetration volume of seed 001 §3.1.3 (there: the boolean intersection of two
// meshes) and the per-character overlap of seed 000 §4.2 (Figure 3), measured on the capsule
// proxies of seed 000 §3.4 instead of the skinned mesh. Points inside several capsules of the same
// body are counted once (union), so a body's self-overlapping joints never inflate v.
//
// Method: column quadrature with exact chords. The integration axis k is the longest axis of the
// region where the two bodies can overlap (union over touching capsule pairs of the intersection of
// their axis-aligned boxes). Every line parallel to k meets each capsule in one interval (a capsule
// is convex) that is computed in closed form (cylinder quadratic + two spheres); the union of A's
// intervals intersected with the union of B's gives the exact chord length f(u, v) of A ∩ B on that
// line. v = ∫∫ f du dv is integrated over the other two axes by adaptive midpoint quadrature on a
// quadtree: a cell is split into 4 while |children estimate - parent estimate| exceeds its share
// (by area) of the tolerance max(abs_tol_m3, rel_tol * v), or while the estimate is zero but the
// bracket below says there may be volume, down to max_depth levels below an 8-cell base grid.
//
// Error bound (rigorous, independent of the tolerance heuristics): for a leaf cell Q of
// half-diagonal h, every line through Q lies within h of the line through Q's centre, and the
// signed distance to a union of capsules is 1-Lipschitz. So the chord of (A ∩ B) on any line in Q
// is at least the centre-line chord of the bodies with every radius shrunk by h, and at most the one
// with radii grown by h. Summing area * chord over the leaves gives lower_m3 <= v <= upper_m3, and
// |volume_m3 - v| <= error_bound_m3() = max(upper - estimate, estimate - lower). The bound is first
// order in the cell size (it charges every surface crossing with a full h), so it is typically
// 10-100x wider than the actual error of the estimate, which is second order away from
// silhouettes; tests/metrics check both against analytic volumes.
#include <span>

#include "framework/core/capsule.hpp"

namespace crowdlab {

struct OverlapOptions {
  double rel_tol = 1e-3;      ///< refinement target relative to the volume estimate (-)
  double abs_tol_m3 = 1e-8;   ///< refinement target floor (m^3; 1e-8 m^3 = 0.01 mL)
  int max_depth = 6;          ///< quadtree levels below the base grid (base 8 cells -> 512 finest)
};

struct OverlapVolume {
  double volume_m3 = 0.0;  ///< the estimate of vol(A ∩ B) (m^3)
  double lower_m3 = 0.0;   ///< rigorous lower bound (m^3)
  double upper_m3 = 0.0;   ///< rigorous upper bound (m^3)
  int chord_evaluations = 0;  ///< lines evaluated (cost measure)
  bool colliding = false;     ///< some capsule of A overlaps some capsule of B (depth > 0)

  double error_bound_m3() const;
};

/// Overlap volume of two capsule sets given in the same (world) frame, metres.
/// Capsules must have finite endpoints and radius > 0 (checked; InputError otherwise).
OverlapVolume overlap_volume(std::span<const Capsule> a, std::span<const Capsule> b,
                             const OverlapOptions& options = {});

}  // namespace crowdlab
