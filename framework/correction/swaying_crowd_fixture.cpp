#include "framework/correction/swaying_crowd_fixture.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "framework/core/error.hpp"
#include "framework/core/forward_kinematics.hpp"
#include "framework/core/seed.hpp"

namespace crowdlab {
namespace {

Quat axis_angle(const Vec3& axis, double angle) {
  return Quat(Eigen::AngleAxisd(angle, axis));
}

}  // namespace

Pose swaying_pose(const BodyShape& shape, const Vec3& floor_position_m, double heading_rad, double phase_rad,
                  double frequency_hz, double amplitude, double t_s) {
  constexpr double kDeg = std::numbers::pi / 180.0;
  const double w = 2.0 * std::numbers::pi * frequency_hz * t_s + phase_rad;
  const double a = amplitude;
  Pose p = Pose::rest(shape);
  // Stand exactly on the floor: the lowest capsule point of the rest pose at y = 0.
  double lowest = 0.0;
  for (const Capsule& c : world_capsules(shape, p))
    lowest = std::min(lowest, std::min(c.a.y(), c.b.y()) - c.radius_m);
  p.root_position_m = floor_position_m + Vec3(0, shape.pelvis_height_m() - lowest, 0);
  p.local_rotations[kPelvis] = axis_angle(Vec3::UnitY(), heading_rad);
  p.local_rotations[kSpine1] = axis_angle(Vec3::UnitZ(), a * 3 * kDeg * std::sin(w));
  p.local_rotations[kSpine2] = axis_angle(Vec3::UnitX(), a * 3 * kDeg * std::sin(w + 1.0));
  p.local_rotations[kSpine3] = axis_angle(Vec3::UnitY(), a * 5 * kDeg * std::sin(w + 2.0));
  p.local_rotations[kNeck] = axis_angle(Vec3::UnitX(), a * 6 * kDeg * std::sin(2 * w));
  p.local_rotations[kHead] = axis_angle(Vec3::UnitY(), a * 8 * kDeg * std::sin(0.5 * w + 0.3));
  for (int side : {+1, -1}) {
    const int shoulder = side > 0 ? kLeftShoulder : kRightShoulder;
    const int elbow = side > 0 ? kLeftElbow : kRightElbow;
    // Left arm points +X in rest: -55 deg about Z lowers it (mirrored for the right arm).
    const double lower = -side * (35 + a * 6 * std::sin(w + side)) * kDeg;
    const double swing = a * 12 * kDeg * std::sin(w + 0.5 * side);
    p.local_rotations[static_cast<size_t>(shoulder)] =
        axis_angle(Vec3::UnitY(), -side * swing) * axis_angle(Vec3::UnitZ(), lower);
    p.local_rotations[static_cast<size_t>(elbow)] =
        axis_angle(Vec3::UnitY(), -side * (20 + a * 15 * std::sin(w + 1.5)) * kDeg);
  }
  return p;
}

CrowdAnimation make_swaying_crowd_fixture(const SwayingCrowdOptions& o) {
  if (o.characters < 1) throw InputError("swaying crowd: characters must be >= 1");
  if (!(o.density_per_m2 > 0.0) || !std::isfinite(o.density_per_m2))
    throw InputError("swaying crowd: density must be > 0");
  if (o.frames < 1) throw InputError("swaying crowd: frames must be >= 1");
  if (!(o.fps > 0.0)) throw InputError("swaying crowd: fps must be > 0");
  CrowdAnimation crowd;
  crowd.meta.fps = o.fps;
  crowd.meta.seed = o.seed;
  crowd.meta.scenario = "swaying_fixture";
  const int side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(o.characters))));
  const double spacing = 1.0 / std::sqrt(o.density_per_m2);
  for (int c = 0; c < o.characters; ++c) {
    Rng rng(derive_seed(o.seed, "swaying_fixture/" + std::to_string(c)));
    const bool female = c % 2 == 0;
    BodyParams bp;
    bp.sex = female ? Sex::kFemale : Sex::kMale;
    bp.height_m =
        std::clamp((female ? 1.59 : 1.71) + (female ? 0.065 : 0.07) * standard_normal(rng), 1.45, 1.95);
    bp.girth = 0.9 + 0.2 * uniform01(rng);
    CharacterAnimation ch;
    ch.name = "c" + std::to_string(1000 + c).substr(1);
    ch.shape = make_procedural_body(bp);
    ch.palette = c % 12;
    const double x = ((c % side) + 0.5 + 0.2 * (uniform01(rng) - 0.5)) * spacing;
    const double z = ((c / side) + 0.5 + 0.2 * (uniform01(rng) - 0.5)) * spacing;
    const double heading = 0.8 * (uniform01(rng) - 0.5);
    const double phase = 2.0 * std::numbers::pi * uniform01(rng);
    const double freq = 0.3 + 0.3 * uniform01(rng);
    ch.frames.reserve(static_cast<size_t>(o.frames));
    for (int f = 0; f < o.frames; ++f)
      ch.frames.push_back(
          swaying_pose(ch.shape, Vec3(x, 0, z), heading, phase, freq, o.sway_amplitude, f / o.fps));
    crowd.characters.push_back(std::move(ch));
  }
  return crowd;
}

}  // namespace crowdlab
