#pragma once
// Proxies that bound what is rendered (issue 27): fits a body's bone capsules (seed 000 §3.4) to its
// rendered mesh (skin, garments, hair, shoes, eyes: core/skinned_mesh.hpp) in the rest pose, so that each
// rendered surface lies within that surface's tolerance of them. make_mpfb2_body() fits each radius to the
// volume of the skin its bone carries, so about half of the skin lies outside the capsules (by up to a few
// cm) and garments and hair more.
//
// Per surface (SurfaceTolerances, metres; +infinity = not bounded, the capsules ignore it):
//   kUniform5mm   every surface within 5 mm (cover_mesh_with_capsules, `correct --cover-mesh`);
//   per_surface   (`correct --fit-proxies`): skin, lips, eyes, brows, garments and shoe uppers 5 mm (what
//                 a viewer reads as a body passing through another); hair 20 mm (it is soft and would
//                 give way in a real contact, and a head capsule grown to the hair pushes heads apart);
//                 shoe soles (shoe vertices within 15 mm of the lowest rest vertex) not bounded: they
//                 meet the ground, never another body, and a foot capsule grown down to them stands
//                 below the ground. (keep_above_floor, which also keeps every capsule above the floor
//                 the rest pose stands on, is off: measured worse in motion, docs/correction.md.)
//
// For every bounded rest-pose vertex v, the capsule it is nearest the surface of, j*(v) = argmin_j
// (|v - axis_j| - r_j), is the one that has to take it in (the least change); then per bone j, over its
// vertices V_j with tolerances t_v:
//   radius only (move_axes false):  r_j <- max(r_j, max_{v in V_j} |v - axis_j| - t_v)
//   with the axis moved (true):     the axis is translated by d, perpendicular to it, chosen on a
//                                   coarse-to-fine grid (2 cm, then 5 mm steps, |d| <= 8 cm) to minimise
//                                   r_j(d) = max(r_min, max_{v in V_j} |v - (axis_j + d)| - t_v), with
//                                   r_min = 1 cm, and with keep_above_floor r_j(d) at most the axis's
//                                   lowest end's height above the floor (the shift first minimises
//                                   what that leaves out). One capsule per bone cannot take in a face in
//                                   front of the head or a belly in front of the spine without growing around
//                                   the back of the head or torso too; moving the axis toward the surface it
//                                   must take in grows it far less (so neighbours are pushed apart less).
// One pass (assignment to the unfitted capsules). The rest-contact pairs (self-collision exclusions) are
// recomputed. Posed, linear-blend skinning bends the mesh at the joints where the rigid capsules do not,
// so coverage in motion is measured separately (metrics/proxy_coverage.hpp).
#include <array>
#include <limits>

#include "framework/core/body_shape.hpp"
#include "framework/core/skinned_mesh.hpp"

namespace crowdlab {

/// Tolerance per SurfaceKind (m); +infinity: the surface is not bounded. sole_height_m: shoe vertices
/// this close to the lowest rest vertex are soles (not bounded when >= 0).
struct SurfaceTolerances {
  std::array<double, static_cast<size_t>(SurfaceKind::kCount)> tolerance_m{};
  double sole_height_m = -1.0;
  /// No capsule reaches below the rest pose's lowest vertex (the floor it stands on) further than its
  /// unfitted radius did: a shoe wider than its foot capsule then stays partly outside (floor_miss_m).
  bool keep_above_floor = false;
  /// Every surface within tol_m (soles too).
  static SurfaceTolerances uniform(double tol_m);
  /// The per-surface choice of the header.
  static SurfaceTolerances per_surface();
};

struct CoverReport {
  double within_before = 0.0;                  ///< share of rest vertices within 5 mm of the capsules, before
  double within_after = 0.0;                   ///< and after
  double bounded_within_after = 0.0;           ///< share of bounded vertices within their tolerance, after
  std::array<double, kJointCount> growth_m{};  ///< radius change per bone (m; negative: shrunk)
  std::array<double, kJointCount> shift_m{};   ///< axis translation per bone (m)
  std::array<double, kJointCount> floor_miss_m{};  ///< how far a bone's farthest vertex stays out (floor cap)
};

/// Fits shape's capsules so that mesh (in the rest pose of `shape`) lies within each surface's tolerance
/// of them (see the header); returns the shares before and after and the change per bone.
CoverReport fit_capsules_to_mesh(BodyShape& shape, const SkinnedMesh& mesh,
                                 const SurfaceTolerances& tolerances, bool move_axes);

/// Grows shape's capsule radii so that mesh (in the rest pose of `shape`) lies within tolerance_m of
/// them (fit_capsules_to_mesh with uniform tolerances, radii only).
CoverReport cover_mesh_with_capsules(BodyShape& shape, const SkinnedMesh& mesh, double tolerance_m = 0.005);

}  // namespace crowdlab
