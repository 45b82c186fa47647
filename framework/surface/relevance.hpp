#pragma once
// Relevant and Offset for crowds on surfaces (seed 002 §3).
//
// Relevant(a, O): which nearby agents may be obstacles for agent a. Three modes:
//   kVisibility (seed 002, ours): Euclidean neighbours, minus those "not visible": the segment from a's
//       feet to the candidate's head (v_head) pierces the 1 m disk at the candidate's feet (normal = its
//       up) or the 1 m disk at a's feet (normal = a's up). The disks approximate the surface each agent
//       stands on. The segment starts `kEyeLift` above a's feet so that it does not touch a's own disk
//       at its origin (the paper starts "from the agent"; a 5 cm lift is our choice).
//   kVisibilityMesh (our refinement, an option; seed 002 §3 calls the disk "not perfect"): the same
//       segment, tested against the real mesh instead of the disks, but only where the disks are: its
//       parts within 1 m of either agent's feet (TriangleBvh). The 1 m disk claims surface that is not
//       there wherever the surface ends or turns within 1 m (a convex edge narrower than the disk: the
//       20 cm sides of a slab, the rim of a storey); there the disk hides agents that are in plain
//       sight and can touch (false negatives), and the mesh test does not. Occluders farther than 1 m
//       from both feet are ignored by both tests alike.
//   kEuclidean (Torchelsen et al. 2010 style baseline): every agent within the neighbour distance.
//   kSurface (surface-path baseline): agents whose geodesic (face-graph) distance is within the
//       neighbour distance.
// Offset(a, o): the union over three spheres stacked along o's up vector (seed 002's OffsetImproved)
//   of the Euclidean offset from a: the vector from a's nearest body sphere to each sphere centre,
//   projected onto a's tangent plane (angle) and its 3D length minus both radii (distance).
#include <string>
#include <vector>

#include "framework/surface/surface_walk.hpp"
#include "framework/surface/triangle_bvh.hpp"

namespace crowdlab {

enum class RelevantMode { kVisibility, kVisibilityMesh, kEuclidean, kSurface };

/// "visibility" | "visibility_mesh" | "euclidean" | "surface".
const char* relevant_mode_name(RelevantMode m);
/// Inverse of relevant_mode_name; InputError naming `key` otherwise.
RelevantMode parse_relevant_mode(const std::string& text, const std::string& key);

/// Body of an agent standing on a surface: a vertical (along "up") stack of three spheres.
struct StackedBody {
  double height_m = 1.8;          ///< agent height, feet to head (metres)
  double sphere_radius_m = 0.25;  ///< radius of each of the three spheres
  /// Distance between consecutive sphere centres along up (metres). 0 (default) = (height - 2r) / 2,
  /// so that the stack spans feet to head. (Seed 002 writes o + i * o_up, i.e. a spacing of one unit
  /// of its normal's length; it leaves the scale open.)
  double sphere_spacing_m = 0.0;
  double spacing() const {
    return sphere_spacing_m > 0 ? sphere_spacing_m : (height_m - 2 * sphere_radius_m) / 2;
  }
  /// Sphere i (0..2) centre: feet + up * (r + i * spacing).
  Vec3 sphere_center(const Vec3& feet, const Vec3& up, int i) const {
    return feet + up * (sphere_radius_m + i * spacing());
  }
};

inline constexpr double kEyeLift = 0.05;        ///< metres; see header comment
inline constexpr double kFeetDiskRadius = 1.0;  ///< seed 002 §3: "one meter radius circle at its feet"

/// True when the segment p -> q crosses the disk (centre, unit normal, radius) at a parameter in (0, 1].
bool segment_pierces_disk(const Vec3& p, const Vec3& q, const Vec3& centre, const Vec3& normal,
                          double radius);

/// Seed 002's visibility test: false when v_head (a's eye point feet_a + kEyeLift * normal_a -> head_b)
/// pierces either agent's feet disk (normals normal_a, normal_b: each agent's normal, seed 002 §3).
bool mutually_visible(const Vec3& feet_a, const Vec3& normal_a, const Vec3& feet_b, const Vec3& normal_b,
                      const Vec3& head_b);
/// Bodies standing along the surface normals (head_b = feet_b + up_b * height).
inline bool mutually_visible(const Vec3& feet_a, const Vec3& up_a, const Vec3& feet_b, const Vec3& up_b,
                             const StackedBody& body) {
  return mutually_visible(feet_a, up_a, feet_b, up_b, feet_b + up_b * body.height_m);
}

/// The kVisibilityMesh test: false when the same segment crosses a triangle of `bvh` within
/// kFeetDiskRadius of feet_a or of feet_b.
bool mutually_visible_near_feet(const Vec3& feet_a, const Vec3& normal_a, const Vec3& feet_b,
                                const Vec3& head_b, const TriangleBvh& bvh);
/// Bodies standing along the surface normals.
inline bool mutually_visible_near_feet(const Vec3& feet_a, const Vec3& up_a, const Vec3& feet_b,
                                       const Vec3& up_b, const StackedBody& body, const TriangleBvh& bvh) {
  return mutually_visible_near_feet(feet_a, up_a, feet_b, feet_b + up_b * body.height_m, bvh);
}

/// One Offset tuple: unit direction in a's tangent plane (world frame) and surface clearance (metres;
/// negative when the spheres overlap).
struct OffsetTuple {
  Vec3 direction = Vec3::Zero();
  double clearance_m = 0.0;
};

/// OffsetImproved (seed 002 §3): three tuples, one per sphere of the obstacle agent.
std::array<OffsetTuple, 3> offset_three_spheres(const Vec3& feet_a, const Vec3& up_a, const Vec3& feet_o,
                                                const Vec3& up_o, const StackedBody& body);

/// Smallest distance between the two sphere stacks minus both radii (metres; < 0 means overlap).
double stacked_clearance(const Vec3& feet_a, const Vec3& up_a, const Vec3& feet_b, const Vec3& up_b,
                         const StackedBody& body);

}  // namespace crowdlab
