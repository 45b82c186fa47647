// Body sampling statistics and the animate_crowd entry point.
#include <tbb/global_control.h>
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>

#include "framework/animation/animate_crowd.hpp"
#include "framework/animation/sample_bodies.hpp"
#include "framework/core/appearance.hpp"
#include "framework/core/error.hpp"
#include "framework/core/forward_kinematics.hpp"
#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_crowd_bodies {

using namespace crowdlab;

TEST_CASE("sampled heights match the world distributions by sex (mean within 3 SE, SD within 10 %)") {
  const int n = test::kSanitized ? 2000 : 20000;
  const std::vector<BodyParams> bodies = sample_bodies(n, 0.5, 2024);
  int women = 0;
  double sum[2] = {0, 0}, sq[2] = {0, 0};
  int count[2] = {0, 0};
  for (const BodyParams& b : bodies) {
    const int s = b.sex == Sex::kFemale ? 0 : 1;
    women += 1 - s;
    sum[s] += b.height_m, sq[s] += b.height_m * b.height_m, ++count[s];
    CHECK(b.girth >= kGirthMin);
    CHECK(b.girth <= kGirthMax);
    CHECK_NOTHROW(make_procedural_body(b));
  }
  CHECK(women == n / 2);
  const HeightDistribution target[2] = {kWorldFemaleHeight, kWorldMaleHeight};
  for (int s = 0; s < 2; ++s) {
    const double mean = sum[s] / count[s];
    const double sd = std::sqrt(sq[s] / count[s] - mean * mean);
    // Truncation at 3 SD shrinks the SD by 1.3 %.
    CHECK(std::abs(mean - target[s].mean_m) < 3 * target[s].sd_m / std::sqrt(count[s]));
    CHECK(sd == Approx(target[s].sd_m).epsilon(0.1));
  }
  CHECK(sample_bodies(10, 0.3, 1)[0].height_m == sample_bodies(10, 0.3, 1)[0].height_m);
  CHECK_THROWS_AS(sample_bodies(3, 1.5, 1), InputError);
}

namespace {
CrowdTrajectories line_crowd(int agents, double speed, int frames) {
  CrowdTrajectories t;
  t.fps = 30;
  t.agents.resize(static_cast<size_t>(agents));
  for (int i = 0; i < agents; ++i)
    for (int k = 0; k < frames; ++k) {
      t.agents[static_cast<size_t>(i)].position_m.emplace_back(0.8 * i, speed * k / 30.0);
      t.agents[static_cast<size_t>(i)].heading_rad.push_back(0.0);
    }
  return t;
}
}  // namespace

TEST_CASE("animate_crowd: names, palettes, validity, stationary vs walking, determinism") {
  AnimationSpec spec;
  AnimationContext ctx;
  ctx.seed = 77;
  ctx.condition_id = "test";
  for (const ScenarioKind scenario : {ScenarioKind::stationary, ScenarioKind::corridor}) {
    ctx.scenario = scenario;
    const CrowdTrajectories t = line_crowd(6, scenario == ScenarioKind::stationary ? 0.0 : 1.2, 90);
    const CrowdAnimation a = animate_crowd(t, Environment{}, spec, ctx);
    const CrowdAnimation b = animate_crowd(t, Environment{}, spec, ctx);
    REQUIRE(a.characters.size() == 6);
    CHECK(a.characters[0].name == "c000");
    CHECK(a.characters[5].name == "c005");
    CHECK(a.frame_count() == 90);
    CHECK(a.meta.scenario == kind_name(scenario));
    CHECK_NOTHROW(validate_crowd(a, "test"));
    int women = 0;
    for (size_t i = 0; i < 6; ++i) {
      women += a.characters[i].shape.params.sex == Sex::kFemale ? 1 : 0;
      for (size_t f = 0; f < 90; f += 7)
        for (int j = 0; j < kJointCount; ++j)
          CHECK(a.characters[i].frames[f].local_rotations[static_cast<size_t>(j)].coeffs() ==
                b.characters[i].frames[f].local_rotations[static_cast<size_t>(j)].coeffs());
      // Root follows the trajectory.
      const Vec3 r = a.characters[i].frames[45].root_position_m;
      CHECK(std::hypot(r.x() - t.agents[i].position_m[45].x(), r.z() - t.agents[i].position_m[45].y()) <
            0.12);
    }
    CHECK(women == 3);
  }
  ctx.scenario = ScenarioKind::corridor;
  CHECK_THROWS_AS(animate_crowd(CrowdTrajectories{}, Environment{}, spec, ctx), InputError);
  spec.body_model = BodyModel::mpfb2;
  CHECK_THROWS_AS(animate_crowd(line_crowd(2, 1, 10), Environment{}, spec, ctx), InputError);
}

TEST_CASE("animate_crowd: dressed crowds of other seeds wear other clothing indices, consecutive ones") {
  // Fails before issue 28's session 13: every dressed crowd of N used the indices 0..N-1, so all crowds
  // wore the same N colour sets (fabric_palette draws per index).
  AnimationSpec spec;
  AnimationContext ctx;
  ctx.condition_id = "test";
  const CrowdTrajectories t = line_crowd(6, 0.0, 10);
  auto clothing_indices = [&](std::uint64_t seed) {
    ctx.seed = seed;
    ctx.shapes.clear();
    ctx.skin_tones.clear();
    for (const BodyParams& params : sample_bodies(6, 0.5, seed)) {
      ctx.skin_tones.push_back(static_cast<int>(ctx.shapes.size() % kSkinToneCount));
      ctx.shapes.push_back(make_procedural_body(params));
    }
    const CrowdAnimation a = animate_crowd(t, Environment{}, spec, ctx);
    std::vector<int> clothing;
    for (size_t i = 0; i < a.characters.size(); ++i) {
      CHECK(skin_tone_of(a.characters[i].palette) == static_cast<int>(i % kSkinToneCount));
      clothing.push_back(clothing_of(a.characters[i].palette));
    }
    std::sort(clothing.begin(), clothing.end());
    for (size_t i = 1; i < clothing.size(); ++i) CHECK(clothing[i] == clothing[i - 1] + 1);
    return clothing;
  };
  const std::vector<int> a = clothing_indices(77), a_again = clothing_indices(77), b = clothing_indices(78);
  CHECK(a == a_again);
  CHECK(a != b);
  CHECK(a.front() != 0);
}

TEST_CASE("animate_crowd gives identical results with one thread and many, shoulder factor is honoured") {
  AnimationSpec spec;
  AnimationContext ctx;
  ctx.seed = 5;
  ctx.scenario = ScenarioKind::pair_crossing;
  ctx.shoulder_count = 2;
  // A crossing pair 0.4 m apart plus a bystander.
  CrowdTrajectories t;
  t.fps = 30;
  t.agents.resize(3);
  for (int k = 0; k < 120; ++k) {
    const double time = k / 30.0;
    t.agents[0].position_m.emplace_back(-0.2, 1.3 * (time - 2.0));
    t.agents[0].heading_rad.push_back(0.0);
    t.agents[1].position_m.emplace_back(0.2, -1.3 * (time - 2.0));
    t.agents[1].heading_rad.push_back(3.14159265358979);
    t.agents[2].position_m.emplace_back(5.0, 1.0 * time);
    t.agents[2].heading_rad.push_back(0.0);
  }
  CrowdAnimation one, many;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = animate_crowd(t, Environment{}, spec, ctx);
  }
  many = animate_crowd(t, Environment{}, spec, ctx);
  for (size_t i = 0; i < 3; ++i)
    for (size_t f = 0; f < 120; ++f) {
      CHECK(one.characters[i].frames[f].root_position_m == many.characters[i].frames[f].root_position_m);
      for (int j = 0; j < kJointCount; ++j)
        CHECK(one.characters[i].frames[f].local_rotations[static_cast<size_t>(j)].coeffs() ==
              many.characters[i].frames[f].local_rotations[static_cast<size_t>(j)].coeffs());
    }
  // Both walkers turn their trunk (spine3 relative to pelvis) near the closest approach (t = 2 s).
  auto trunk_twist = [](const Pose& p) {
    return Eigen::AngleAxisd(p.local_rotations[kSpine1] * p.local_rotations[kSpine2] *
                             p.local_rotations[kSpine3])
        .angle();
  };
  for (size_t i = 0; i < 2; ++i) CHECK(trunk_twist(many.characters[i].frames[60]) > 0.4);
  ctx.shoulder_count = 0;
  const CrowdAnimation none = animate_crowd(t, Environment{}, spec, ctx);
  for (size_t i = 0; i < 2; ++i) CHECK(trunk_twist(none.characters[i].frames[60]) < 0.2);
}

}  // namespace test_crowd_bodies
