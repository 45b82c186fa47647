#pragma once
// BodyShape: the immutable geometry of one character: rest joint offsets and one capsule per bone.
//
// Frames: every bone frame coincides with its joint; in the rest pose (identity local rotations)
// all bone frames are aligned with the character frame (+Y up, +Z forward, +X character's left),
// so `joint_offsets_m` and capsule endpoints read directly as T-pose geometry.
#include <array>
#include <string>
#include <utility>
#include <vector>

#include "framework/core/capsule.hpp"
#include "framework/core/skeleton.hpp"

namespace crowdlab {

enum class Sex { kFemale, kMale };
std::string_view to_string(Sex sex);

/// Parameters of the procedural body (see make_procedural_body()).
struct BodyParams {
  Sex sex = Sex::kMale;
  double height_m = 1.75;  ///< standing height, floor to vertex (metres); valid range [1.2, 2.3]
  double girth = 1.0;      ///< multiplies every capsule radius; 1 = average build; valid [0.7, 1.5]
};

struct BodyShape {
  BodyParams params;
  /// offset of joint j from its parent joint, in the parent's bone frame (metres), (24 x 3).
  /// For the root this is the pelvis position above the floor in the rest pose.
  std::array<Vec3, kJointCount> joint_offsets_m{};
  /// capsule of bone j in bone j's frame (metres), (24).
  std::array<Capsule, kJointCount> capsules{};
  /// bone pairs (i < j) whose capsules overlap in the rest pose; excluded from self-collision
  /// (seed 000 §3.4: "adjacent capsule pairs, which we identify as those that collide in T-pose").
  std::vector<std::pair<int, int>> rest_contact_pairs;

  /// Height of the pelvis joint above the feet in the rest pose (metres).
  double pelvis_height_m() const { return joint_offsets_m[kPelvis].y(); }
  /// Sum of capsule volumes (m^3). Overlapping capsules are counted twice; see metrics for the union.
  double capsule_volume_sum_m3() const;
};

/// A procedural body from anthropometric proportions.
/// Joint heights and segment lengths are fractions of stature from Winter, "Biomechanics and Motor
/// Control of Human Movement" (4th ed., 2009, Fig. 4.1, after Drillis & Contini 1966). Capsule radii are
/// fractions of stature fitted to mean segment circumferences of adults (ANSUR II 2012 means: thigh
/// ~0.60 m, calf ~0.38 m, biceps ~0.32 m, forearm ~0.28 m, neck ~0.38 m circumference for men), and
/// tuned so that a 1.75 m male's capsule union is ~70 litres (a 75 kg man at ~1.06 kg/L).
/// Women get narrower shoulders and wider hips relative to stature (Winter's table is sex-neutral;
/// the 5 % adjustments follow ANSUR II biacromial / hip-breadth ratios).
/// Throws InputError when params are outside their valid ranges or not finite.
BodyShape make_procedural_body(const BodyParams& params);

/// Recomputes shape.rest_contact_pairs from the rest pose (capsule pairs that overlap there).
void compute_rest_contact_pairs(BodyShape& shape);

/// Checks a shape loaded from a file: finite offsets, radii in (0, 1] m, no zero-length bone but the root's,
/// a rest-pose body within 4 m on each axis (limits in body_shape.cpp). Throws InputError naming the joint.
void validate_body_shape(const BodyShape& shape, const std::string& context);

}  // namespace crowdlab
