// The procedural body, the skeleton topology and forward kinematics.
#include <catch2/catch.hpp>
#include <cmath>
#include <set>
#include <vector>

#include "framework/core/body_shape.hpp"
#include "framework/core/error.hpp"
#include "framework/core/forward_kinematics.hpp"
#include "framework/core/seed.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_body {

using namespace crowdlab;

namespace {
// Union volume of the capsules by stratified sampling on a 5 mm grid (error well under 1 %).
double union_volume_m3(const WorldCapsules& caps) {
  Vec3 lo = Vec3::Constant(1e9), hi = Vec3::Constant(-1e9);
  for (const auto& c : caps) {
    lo = lo.cwiseMin(c.a.cwiseMin(c.b) - Vec3::Constant(c.radius_m));
    hi = hi.cwiseMax(c.a.cwiseMax(c.b) + Vec3::Constant(c.radius_m));
  }
  const double h = 0.005;
  long inside = 0;
  for (double x = lo.x() + h / 2; x < hi.x(); x += h)
    for (double y = lo.y() + h / 2; y < hi.y(); y += h)
      for (double z = lo.z() + h / 2; z < hi.z(); z += h) {
        const Vec3 p(x, y, z);
        for (const auto& c : caps) {
          const auto cp = segment_closest_points(c.a, c.b, p, p);
          if (cp.distance_m < c.radius_m) {
            ++inside;
            break;
          }
        }
      }
  return inside * h * h * h;
}
}  // namespace

TEST_CASE("SMPL topology: parents precede children, names round-trip, mirror is an involution") {
  for (int j = 1; j < kJointCount; ++j) CHECK(kJointParent[static_cast<size_t>(j)] < j);
  CHECK(kJointParent[0] == -1);
  for (int j = 0; j < kJointCount; ++j) {
    CHECK(joint_from_name(joint_name(j)) == j);
    CHECK(mirror_joint(mirror_joint(j)) == j);
  }
  CHECK(joint_name(kLeftWrist) == "left_wrist");
  CHECK(mirror_joint(kLeftElbow) == kRightElbow);
  CHECK(!joint_from_name("tail").has_value());
}

TEST_CASE("procedural body stands on the ground with its head at stature") {
  for (Sex sex : {Sex::kFemale, Sex::kMale})
    for (double h : {1.5, 1.75, 1.95}) {
      const BodyShape s = make_procedural_body({sex, h, 1.0});
      const WorldCapsules caps = world_capsules(s, Pose::rest(s));
      double min_y = 1e9, max_y = -1e9;
      for (const auto& c : caps) {
        min_y = std::min({min_y, c.a.y() - c.radius_m, c.b.y() - c.radius_m});
        max_y = std::max({max_y, c.a.y() + c.radius_m, c.b.y() + c.radius_m});
      }
      CHECK(min_y == Approx(0.0).margin(0.01 * h));
      CHECK(max_y == Approx(h).margin(0.015 * h));
    }
}

TEST_CASE("a 1.75 m man's capsule union is 65-80 litres") {
  const BodyShape s = make_procedural_body({Sex::kMale, 1.75, 1.0});
  const double litres = union_volume_m3(world_capsules(s, Pose::rest(s))) * 1000.0;
  INFO("union volume " << litres << " L");
  CHECK(litres > 65.0);
  CHECK(litres < 80.0);
}

TEST_CASE("rest contact pairs include every parent-child pair and no left-right limb pair") {
  const BodyShape s = make_procedural_body({Sex::kFemale, 1.62, 1.0});
  auto has = [&](int a, int b) {
    for (auto [i, j] : s.rest_contact_pairs)
      if ((i == a && j == b) || (i == b && j == a)) return true;
    return false;
  };
  for (int j = 1; j < kJointCount; ++j) CHECK(has(j, kJointParent[static_cast<size_t>(j)]));
  CHECK_FALSE(has(kLeftWrist, kRightWrist));
  CHECK_FALSE(has(kLeftKnee, kRightKnee));
  CHECK_FALSE(has(kHead, kLeftHand));
}

TEST_CASE("forward kinematics: rotations compose and round-trip through bone transforms") {
  const BodyShape s = make_procedural_body({Sex::kMale, 1.8, 1.1});
  Rng rng(3);
  for (int k = 0; k < 20; ++k) {
    Pose p;
    p.root_position_m = Vec3(standard_normal(rng), 1.0, standard_normal(rng));
    for (auto& q : p.local_rotations)
      q = Quat(standard_normal(rng), standard_normal(rng), standard_normal(rng), standard_normal(rng))
              .normalized();
    const Pose back = pose_from_bone_transforms(forward_kinematics(s, p));
    CHECK((back.root_position_m - p.root_position_m).norm() < 1e-12);
    for (int j = 0; j < kJointCount; ++j)
      CHECK(back.local_rotations[static_cast<size_t>(j)].angularDistance(
                p.local_rotations[static_cast<size_t>(j)]) < 1e-9);
  }
  // Bending the left elbow by 90 degrees about -Y moves the wrist forward (+Z) by the forearm length.
  Pose bent = Pose::rest(s);
  bent.local_rotations[kLeftElbow] = Quat(Eigen::AngleAxisd(-M_PI / 2, Vec3::UnitY()));
  const auto rest_j = joint_positions(s, Pose::rest(s));
  const auto bent_j = joint_positions(s, bent);
  const double forearm = s.joint_offsets_m[kLeftWrist].norm();
  CHECK((bent_j[kLeftWrist] - bent_j[kLeftElbow]).isApprox(Vec3(0, 0, forearm)));
  CHECK((bent_j[kLeftElbow] - rest_j[kLeftElbow]).norm() < 1e-12);
}

TEST_CASE("bad bodies and poses are rejected with the joint named") {
  CHECK_THROWS_AS(make_procedural_body({Sex::kMale, 0.5, 1.0}), InputError);
  CHECK_THROWS_AS(make_procedural_body({Sex::kMale, 1.7, std::nan("")}), InputError);
  BodyShape s = make_procedural_body({Sex::kMale, 1.7, 1.0});
  Pose p = Pose::rest(s);
  p.local_rotations[kLeftKnee].w() = std::nan("");
  CHECK_THROWS_WITH(validate_pose(p, "test"), Catch::Contains("left_knee"));
  s.joint_offsets_m[kRightElbow].setZero();
  CHECK_THROWS_WITH(validate_body_shape(s, "test"), Catch::Contains("right_elbow"));
}

TEST_CASE("implausible bodies from files are refused before the corrector samples them (issue 21)") {
  // Joint offsets of 1e300 or 65535 m, or a capsule radius of 1e6 m, kept `correct` voxelising the body
  // for minutes (at 1e300 its x += 0.025 never advanced).
  const BodyShape good = make_procedural_body({Sex::kFemale, 1.9, 1.3});
  CHECK_NOTHROW(validate_body_shape(good, "test"));
  BodyShape s = good;
  s.joint_offsets_m[kLeftWrist] = Vec3(1e300, 0, 0);
  CHECK_THROWS_WITH(validate_body_shape(s, "crowd.glb"),
                    Catch::Contains("crowd.glb") && Catch::Contains("rest-pose body spans"));
  s = good;
  s.joint_offsets_m[kRightElbow] = Vec3(0, 65535, 0);
  CHECK_THROWS_WITH(validate_body_shape(s, "crowd.glb"), Catch::Contains("limit of 4 m"));
  s = good;
  s.capsules[kPelvis].radius_m = 1e6;
  CHECK_THROWS_WITH(validate_body_shape(s, "crowd.glb"),
                    Catch::Contains("pelvis") && Catch::Contains("capsule radius"));
  Pose far = Pose::rest(good);
  far.root_position_m = Vec3(1e300, 0, 0);
  CHECK_THROWS_WITH(validate_pose(far, "frame 3"), Catch::Contains("frame 3") && Catch::Contains("100 km"));
}

TEST_CASE("derived seeds are stable and independent of derivation order") {
  CHECK(stable_hash("abc") == 0xe71fa2190541574bULL);
  CHECK(derive_seed(1, "a") != derive_seed(1, "b"));
  CHECK(derive_seed(1, "a") == derive_seed(1, "a"));
  Rng r1(derive_seed(42, "x")), r2(derive_seed(42, "x"));
  for (int i = 0; i < 10; ++i) CHECK(uniform01(r1) == uniform01(r2));
}

TEST_CASE("the word hash of a block of doubles changes with any one element, sign and length included") {
  std::vector<double> data(1000);
  for (size_t i = 0; i < data.size(); ++i) data[i] = 0.001 * static_cast<double>(i * i % 997);
  const std::uint64_t base = stable_hash_words(data);
  CHECK(stable_hash_words(data) == base);
  std::set<std::uint64_t> seen = {base};
  for (const size_t at : {size_t{0}, size_t{1}, size_t{500}, size_t{999}}) {
    std::vector<double> changed = data;
    changed[at] = std::nextafter(changed[at], 1e9);  // the lowest bit
    CHECK(seen.insert(stable_hash_words(changed)).second);
    changed[at] = -data[at];  // the sign bit (0.0 becomes -0.0)
    CHECK(seen.insert(stable_hash_words(changed)).second);
  }
  std::vector<double> swapped = data;
  std::swap(swapped[10], swapped[11]);
  CHECK(seen.insert(stable_hash_words(swapped)).second);
  CHECK(seen.insert(stable_hash_words(std::span(data).first(999))).second);
  CHECK(stable_hash_words({}) != stable_hash_words(std::vector<double>{0.0}));
}

}  // namespace test_body
