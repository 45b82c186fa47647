#include "framework/core/body_shape.hpp"

#include <cmath>

#include "framework/core/capsule_box.hpp"
#include "framework/core/error.hpp"
#include "framework/core/forward_kinematics.hpp"

namespace crowdlab {

std::string_view to_string(Sex sex) {
  return sex == Sex::kFemale ? "female" : "male";
}

double BodyShape::capsule_volume_sum_m3() const {
  double v = 0.0;
  for (const Capsule& c : capsules) v += c.volume_m3();
  return v;
}

namespace {

// Heights above the floor as fractions of stature H (Winter 2009, Fig. 4.1).
constexpr double kAnkleH = 0.039, kKneeH = 0.285, kHipH = 0.530;
constexpr double kPelvisH = 0.560;  // SMPL's pelvis joint sits a little above the hip centres
constexpr double kSpine1H = 0.610, kSpine2H = 0.680, kSpine3H = 0.745;
constexpr double kNeckH = 0.830, kHeadH = 0.880, kShoulderH = 0.805;
// Lateral / longitudinal distances as fractions of H.
constexpr double kHipHalfWidth = 0.052;       // hip-joint centres ~0.10 H apart
constexpr double kCollarHalfWidth = 0.030;    // sterno-clavicular region
constexpr double kShoulderHalfWidth = 0.110;  // gleno-humeral centres (biacromial 0.259 H, minus soft tissue)
constexpr double kUpperArm = 0.186, kForearm = 0.146, kPalm = 0.060;
constexpr double kFootForward = 0.100;  // ankle -> ball of foot (foot length 0.152 H)
constexpr double kBallH = 0.020;

Capsule make(double ax, double ay, double az, double bx, double by, double bz, double r, double H) {
  return {Vec3(ax, ay, az) * H, Vec3(bx, by, bz) * H, r * H};
}

}  // namespace

BodyShape make_procedural_body(const BodyParams& p) {
  if (!std::isfinite(p.height_m) || p.height_m < 1.2 || p.height_m > 2.3)
    throw InputError("body height_m must be in [1.2, 2.3] m, got " + std::to_string(p.height_m));
  if (!std::isfinite(p.girth) || p.girth < 0.7 || p.girth > 1.5)
    throw InputError("body girth must be in [0.7, 1.5], got " + std::to_string(p.girth));

  const double H = p.height_m;
  const bool female = p.sex == Sex::kFemale;
  const double shoulder_scale = female ? 0.95 : 1.0;
  const double hip_scale = female ? 1.05 : 1.0;

  BodyShape s;
  s.params = p;
  auto& o = s.joint_offsets_m;
  o[kPelvis] = Vec3(0, kPelvisH, 0) * H;
  for (int side : {+1, -1}) {
    const int hip = side > 0 ? kLeftHip : kRightHip;
    const int knee = side > 0 ? kLeftKnee : kRightKnee;
    const int ankle = side > 0 ? kLeftAnkle : kRightAnkle;
    const int foot = side > 0 ? kLeftFoot : kRightFoot;
    const int collar = side > 0 ? kLeftCollar : kRightCollar;
    const int shoulder = side > 0 ? kLeftShoulder : kRightShoulder;
    const int elbow = side > 0 ? kLeftElbow : kRightElbow;
    const int wrist = side > 0 ? kLeftWrist : kRightWrist;
    const int hand = side > 0 ? kLeftHand : kRightHand;
    o[hip] = Vec3(side * kHipHalfWidth * hip_scale, kHipH - kPelvisH, 0) * H;
    o[knee] = Vec3(0, kKneeH - kHipH, 0) * H;
    o[ankle] = Vec3(0, kAnkleH - kKneeH, 0) * H;
    o[foot] = Vec3(0, kBallH - kAnkleH, kFootForward) * H;
    o[collar] = Vec3(side * kCollarHalfWidth * shoulder_scale, (kShoulderH + 0.005) - kSpine3H, -0.01) * H;
    o[shoulder] = Vec3(side * (kShoulderHalfWidth - kCollarHalfWidth) * shoulder_scale, -0.005, 0.0) * H;
    o[elbow] = Vec3(side * kUpperArm, 0, 0) * H;
    o[wrist] = Vec3(side * kForearm, 0, 0) * H;
    o[hand] = Vec3(side * kPalm, 0, 0) * H;
  }
  o[kSpine1] = Vec3(0, kSpine1H - kPelvisH, -0.005) * H;
  o[kSpine2] = Vec3(0, kSpine2H - kSpine1H, 0.0) * H;
  o[kSpine3] = Vec3(0, kSpine3H - kSpine2H, 0.005) * H;
  o[kNeck] = Vec3(0, kNeckH - kSpine3H, -0.01) * H;
  o[kHead] = Vec3(0, kHeadH - kNeckH, 0.01) * H;

  // Capsules in bone frames (fractions of H); radii scaled by girth below.
  auto& c = s.capsules;
  const double hw = 0.040 * hip_scale, sw = 0.036 * shoulder_scale;
  c[kPelvis] = make(-hw, -0.010, 0.000, hw, -0.010, 0.000, 0.060, H);
  c[kSpine1] = make(-0.036, 0.015, 0.000, 0.036, 0.015, 0.000, 0.058, H);
  c[kSpine2] = make(-0.038, 0.020, 0.004, 0.038, 0.020, 0.004, 0.060, H);
  c[kSpine3] = make(-sw, 0.025, 0.002, sw, 0.025, 0.002, 0.062, H);
  c[kNeck] = make(0, 0.000, 0.000, 0, 0.040, 0.005, 0.032, H);
  c[kHead] = make(0, 0.035, 0.012, 0, 0.068, 0.010, 0.052, H);
  for (int side : {+1, -1}) {
    const double x = side;
    const bool left = side > 0;
    c[left ? kLeftHip : kRightHip] = make(0, -0.030, 0, 0, kKneeH - kHipH + 0.020, 0, 0.050, H);
    c[left ? kLeftKnee : kRightKnee] = make(0, -0.020, 0, 0, kAnkleH - kKneeH + 0.022, -0.004, 0.033, H);
    c[left ? kLeftAnkle : kRightAnkle] = make(0, -0.014, -0.022, 0, -0.016, 0.072, 0.025, H);
    c[left ? kLeftFoot : kRightFoot] = make(0, -0.004, 0.004, 0, -0.004, 0.034, 0.016, H);
    c[left ? kLeftCollar : kRightCollar] = make(x * 0.010, 0, -0.004, x * 0.070, -0.004, -0.004, 0.036, H);
    c[left ? kLeftShoulder : kRightShoulder] = make(x * 0.020, 0, 0, x * (kUpperArm - 0.020), 0, 0, 0.030, H);
    c[left ? kLeftElbow : kRightElbow] = make(x * 0.015, 0, 0, x * (kForearm - 0.012), 0, 0, 0.024, H);
    c[left ? kLeftWrist : kRightWrist] = make(x * 0.010, 0, 0, x * (kPalm - 0.008), 0, 0, 0.019, H);
    c[left ? kLeftHand : kRightHand] = make(x * 0.008, 0, 0, x * 0.045, 0, 0, 0.012, H);
  }
  for (Capsule& cap : c) cap.radius_m *= p.girth;
  compute_rest_contact_pairs(s);
  return s;
}

void compute_rest_contact_pairs(BodyShape& shape) {
  Pose rest = Pose::rest(shape);
  const WorldCapsules world = world_capsules(shape, rest);
  shape.rest_contact_pairs.clear();
  for (int i = 0; i < kJointCount; ++i)
    for (int j = i + 1; j < kJointCount; ++j)
      if (capsule_contact(world[static_cast<size_t>(i)], world[static_cast<size_t>(j)]).depth_m > -1e-3)
        shape.rest_contact_pairs.emplace_back(i, j);
}

namespace {
// Plausible magnitudes for a human body read from a file (issue 21: a joint offset of 1e300 m or a capsule
// radius of 1e6 m stalled the corrector, which samples the rest-pose body on a 2.5 cm grid). The tallest
// recorded human was 2.72 m: the limits admit any real body and stop absurd ones.
constexpr double kMaxCapsuleRadius_m = 1.0;
constexpr double kMaxBodyExtent_m = 4.0;  // rest-pose bounding box, capsules included, per axis
}  // namespace

void validate_body_shape(const BodyShape& shape, const std::string& context) {
  for (int j = 0; j < kJointCount; ++j) {
    const std::string where = context + ": joint '" + std::string(joint_name(j)) + "'";
    const Vec3& off = shape.joint_offsets_m[static_cast<size_t>(j)];
    const Capsule& cap = shape.capsules[static_cast<size_t>(j)];
    if (!off.allFinite() || !cap.a.allFinite() || !cap.b.allFinite() || !std::isfinite(cap.radius_m))
      throw InputError(where + " has a non-finite offset or capsule");
    if (!(cap.radius_m > 0.0)) throw InputError(where + " has a capsule radius <= 0");
    if (cap.radius_m > kMaxCapsuleRadius_m)
      throw InputError(where + " has a capsule radius of " + std::to_string(cap.radius_m) +
                       " m, more than the limit of 1 m (kMaxCapsuleRadius_m)");
    if (j != kPelvis && off.norm() < 1e-6) throw InputError(where + " has a zero-length bone to its parent");
  }
  // The whole rest-pose body, relative to its pelvis (the root offset places it, not its size).
  const Aabb body = capsules_box(world_capsules(shape, Pose::rest(shape)));
  const double extent_m = (body.hi - body.lo).maxCoeff();
  if (!(extent_m <= kMaxBodyExtent_m))
    throw InputError(context + ": the rest-pose body spans " + std::to_string(extent_m) +
                     " m, more than the limit of 4 m (kMaxBodyExtent_m; joint offsets or capsules are not in "
                     "metres, or are corrupt)");
}

}  // namespace crowdlab
