// Crowd-level measures: V (seed 001 Eq. 1) on hand-made sequences, per-character overlap, collision
// events, penetration depth, union semantics over several neighbours, and thread-count determinism.
#include <tbb/global_control.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <vector>

#include "framework/core/error.hpp"
#include "framework/core/forward_kinematics.hpp"
#include "framework/metrics/character_overlap.hpp"
#include "framework/metrics/measure_crowd.hpp"
#include "framework/metrics/volume_index.hpp"
#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_crowd_metrics {

using namespace crowdlab;

namespace {

CharacterAnimation walker(const std::string& name, Sex sex, double height, const std::vector<Vec3>& roots,
                          double heading) {
  CharacterAnimation c;
  c.name = name;
  c.shape = make_procedural_body({sex, height, 1.0});
  for (const Vec3& r : roots) {
    Pose p = Pose::rest(c.shape);
    p.root_position_m = Vec3(r.x(), c.shape.pelvis_height_m(), r.z());
    p.local_rotations[kPelvis] = Quat(Eigen::AngleAxisd(heading, Vec3::UnitY()));
    c.frames.push_back(p);
  }
  return c;
}

CrowdAnimation two_characters(const std::vector<double>& x_of_second) {
  CrowdAnimation crowd;
  crowd.meta.fps = 30.0;
  std::vector<Vec3> fixed(x_of_second.size(), Vec3::Zero()), moving;
  for (double x : x_of_second) moving.push_back(Vec3(x, 0, 0));
  crowd.characters.push_back(walker("c000", Sex::kMale, 1.78, fixed, 0.0));
  crowd.characters.push_back(walker("c001", Sex::kFemale, 1.65, moving, 3.14159));
  return crowd;
}

}  // namespace

TEST_CASE("V_i is the mean cube root over colliding frames (seed 001 Eq. 1)") {
  const std::vector<double> v = {0.0, 8e-3, 0.0, 1e-3, 0.0};
  CHECK(mean_cube_root_volume(v) == Approx((0.2 + 0.1) / 2));
  CHECK(mean_cube_root_volume(std::vector<double>{0.0, 0.0}) == 0.0);
  CHECK(mean_cube_root_volume(std::vector<double>{}) == 0.0);
  CHECK(mean_cube_root_volume(std::vector<double>{2.7e-5}) == Approx(0.03));
  CHECK_THROWS_AS(mean_cube_root_volume(std::vector<double>{0.0, -1e-6}), InputError);
  CHECK_THROWS_AS(mean_cube_root_volume(std::vector<double>{std::nan("")}), InputError);
}

TEST_CASE("two characters: events, frames, symmetric per-character overlap, depth") {
  // Apart, apart, overlapping, deeper, apart, overlapping: 2 collision events, 3 colliding frames.
  const CrowdAnimation crowd = two_characters({2.0, 1.5, 0.45, 0.3, 1.2, 0.4});
  const CrowdMetrics m = measure_crowd(crowd);
  REQUIRE(m.frames == 6);
  CHECK(m.collision_count == 2);
  CHECK(m.colliding_frames == 3);
  REQUIRE(m.pairs.size() == 1);
  CHECK(m.pairs[0].collision_events == 2);
  CHECK(m.pairs[0].colliding_frames == 3);
  for (int f : {0, 1, 4}) {
    CHECK(m.per_frame[static_cast<size_t>(f)].mean_character_overlap_m3 == 0.0);
    CHECK(m.per_frame[static_cast<size_t>(f)].max_penetration_depth_m == 0.0);
  }
  // Closer -> more overlap and deeper penetration.
  CHECK(m.per_frame[3].total_pair_overlap_m3 > m.per_frame[2].total_pair_overlap_m3);
  CHECK(m.per_frame[3].max_penetration_depth_m >= m.per_frame[2].max_penetration_depth_m - 1e-6);
  // With two characters, each one's overlap with "all others" is the pair's volume: the mean over
  // the two equals the pair volume (up to quadrature: A and B swap roles).
  for (int f : {2, 3, 5}) {
    const FrameMetrics& fm = m.per_frame[static_cast<size_t>(f)];
    CHECK(fm.total_pair_overlap_m3 > 0.0);
    CHECK(fm.mean_character_overlap_m3 == Approx(fm.total_pair_overlap_m3).epsilon(0.01));
  }
  // Penetration depth against a brute-force loop over capsule pairs.
  for (int f = 0; f < m.frames; ++f) {
    const WorldCapsules a =
        world_capsules(crowd.characters[0].shape, crowd.characters[0].frames[static_cast<size_t>(f)]);
    const WorldCapsules b =
        world_capsules(crowd.characters[1].shape, crowd.characters[1].frames[static_cast<size_t>(f)]);
    double depth = 0.0;
    for (const Capsule& ca : a)
      for (const Capsule& cb : b) {
        const double d =
            ca.radius_m + cb.radius_m - segment_closest_points(ca.a, ca.b, cb.a, cb.b).distance_m;
        depth = std::max(depth, d);
      }
    CHECK(m.per_frame[static_cast<size_t>(f)].max_penetration_depth_m == Approx(depth).margin(1e-12));
  }
  // V over the clip, and litres for Figure 3.
  std::vector<double> v;
  for (const FrameMetrics& fm : m.per_frame) v.push_back(fm.total_pair_overlap_m3);
  CHECK(m.volume_index_m == Approx(mean_cube_root_volume(v)));
  double mean = 0.0;
  for (const FrameMetrics& fm : m.per_frame) mean += fm.mean_character_overlap_m3;
  CHECK(m.mean_character_overlap_l == Approx(1000.0 * mean / m.frames));
}

TEST_CASE("a character's overlap with all others counts a shared region once") {
  // Three characters at one spot: v_0 = vol(B0 ∩ (B1 ∪ B2)) lies between the largest pairwise
  // volume and the sum of the two pairwise volumes (strictly below when B1 and B2 overlap too).
  CrowdAnimation crowd;
  crowd.meta.fps = 30;
  crowd.characters.push_back(walker("c0", Sex::kMale, 1.75, {Vec3(0, 0, 0)}, 0.0));
  crowd.characters.push_back(walker("c1", Sex::kMale, 1.75, {Vec3(0.25, 0, 0.05)}, 0.3));
  crowd.characters.push_back(walker("c2", Sex::kFemale, 1.7, {Vec3(0.2, 0, -0.1)}, -0.4));
  std::vector<WorldCapsules> bodies;
  std::vector<Aabb> bounds;
  for (const auto& c : crowd.characters) {
    bodies.push_back(world_capsules(c.shape, c.frames[0]));
    bounds.push_back(capsules_box(bodies.back()));
  }
  const double v01 = character_overlap(bodies[0], bodies[1]).volume_m3;
  const double v02 = character_overlap(bodies[0], bodies[2]).volume_m3;
  const double v0 = overlap_with_others(bodies, bounds, 0).volume_m3;
  CHECK(v0 >= 0.99 * std::max(v01, v02));
  CHECK(v0 < 0.98 * (v01 + v02));
}

TEST_CASE("measure_crowd gives identical results with 1 thread and many") {
  CrowdAnimation crowd;
  crowd.meta.fps = 30;
  for (int i = 0; i < 6; ++i) {
    std::vector<Vec3> roots;
    for (int f = 0; f < (test::kSanitized ? 4 : 12); ++f)
      roots.push_back(Vec3(0.3 * std::cos(i + 0.1 * f), 0, 0.3 * std::sin(1.3 * i + 0.05 * f)));
    crowd.characters.push_back(
        walker("c" + std::to_string(i), i % 2 ? Sex::kFemale : Sex::kMale, 1.6 + 0.05 * i, roots, 0.7 * i));
  }
  CrowdMetrics serial, parallel;
  {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    serial = measure_crowd(crowd);
  }
  parallel = measure_crowd(crowd);
  REQUIRE(serial.frames == parallel.frames);
  for (size_t f = 0; f < serial.per_frame.size(); ++f) {
    CHECK(serial.per_frame[f].mean_character_overlap_m3 == parallel.per_frame[f].mean_character_overlap_m3);
    CHECK(serial.per_frame[f].total_pair_overlap_m3 == parallel.per_frame[f].total_pair_overlap_m3);
    CHECK(serial.per_frame[f].max_penetration_depth_m == parallel.per_frame[f].max_penetration_depth_m);
  }
  CHECK(serial.mean_character_overlap_l == parallel.mean_character_overlap_l);
  CHECK(serial.collision_count == parallel.collision_count);
  CHECK(serial.mean_character_overlap_l > 0.0);
}

TEST_CASE("measure_crowd rejects an invalid crowd") {
  CrowdAnimation crowd = two_characters({0.5, 0.4});
  crowd.characters[1].frames.pop_back();
  CHECK_THROWS_AS(measure_crowd(crowd), InputError);
}

}  // namespace test_crowd_metrics
