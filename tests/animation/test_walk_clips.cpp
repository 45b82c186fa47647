// Walking from motion-capture clips (walk_from_clips.hpp) on the Bandai-Namco walks: gait cycles,
// the speed blend, trajectory following, planted feet, seamless cycles, errors naming the file.
#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>

#include "framework/animation/animate_crowd.hpp"
#include "framework/animation/bvh.hpp"
#include "framework/animation/foot_skate.hpp"
#include "framework/animation/retarget.hpp"
#include "framework/animation/rotation_helpers.hpp"
#include "framework/animation/walk_from_clips.hpp"
#include "framework/core/error.hpp"
#include "framework/core/forward_kinematics.hpp"
#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_walk_clips {

using namespace crowdlab;

namespace {

AgentTrajectory line_at(double speed, double seconds, double fps) {
  AgentTrajectory t;
  for (int k = 0; k < static_cast<int>(seconds * fps); ++k) {
    t.position_m.emplace_back(0.3, speed * k / fps);
    t.heading_rad.push_back(0.0);
  }
  return t;
}

AgentTrajectory arc(double speed, double radius, double seconds, double fps) {
  AgentTrajectory t;
  for (int k = 0; k < static_cast<int>(seconds * fps); ++k) {
    const double a = speed * k / fps / radius;
    t.position_m.emplace_back(radius * (1 - std::cos(a)), radius * std::sin(a));
    t.heading_rad.push_back(a);
  }
  return t;
}

std::vector<WalkCycle> cycles_for(const std::filesystem::path& dir, const BodyShape& s,
                                  const std::vector<std::string>& files) {
  std::vector<WalkCycle> out;
  for (const std::string& f : files)
    out.push_back(extract_walk_cycle(retarget_bvh(import_bvh(dir / f), s), s, f));
  return out;
}

/// Largest joint step between consecutive frames (metres).
double max_step(const BodyShape& s, const Pose& a, const Pose& b) {
  const auto ja = joint_positions(s, a), jb = joint_positions(s, b);
  double m = 0;
  for (size_t j = 0; j < ja.size(); ++j) m = std::max(m, (ja[j] - jb[j]).norm());
  return m;
}

}  // namespace

TEST_CASE("walk clips: one seamless gait cycle per clip, with its measured speed and contacts") {
  const auto dir = test::shared_data("bandai-namco-1");
  if (dir.empty()) return;
  const BodyShape s = make_procedural_body({Sex::kMale, 1.75, 1.0});
  const std::vector<WalkCycle> cycles = cycles_for(
      dir, s,
      {"dataset-1_walk_normal_001.bvh", "dataset-1_walk_tired_001.bvh", "dataset-1_walk_proud_001.bvh"});
  for (const WalkCycle& c : cycles) {
    const double seconds = static_cast<double>(c.frames.size()) / c.fps;
    INFO(c.source << ": " << c.speed_mps << " m/s, cycle " << seconds << " s, " << c.distance_m << " m");
    CHECK(seconds > 0.6);
    CHECK(seconds < 2.0);
    CHECK(c.speed_mps > 0.5);
    CHECK(c.speed_mps < 2.0);
    // Both feet have a stance and a swing; the left one starts in contact.
    for (size_t side = 0; side < 2; ++side) {
      size_t down = 0;
      for (auto v : c.contact[side]) down += v;
      CHECK(down > c.frames.size() / 5);
      CHECK(down < c.frames.size());
    }
    CHECK(c.contact[0].front() == 1);
    // Loop continuity: the wrap step (last -> first) is no larger than the largest in-cycle step.
    double largest = 0;
    for (size_t k = 1; k < c.frames.size(); ++k)
      largest = std::max(largest, max_step(s, c.frames[k - 1], c.frames[k]));
    // (Travel frame: the straight-line advance is removed from every frame alike.)
    const double wrap = max_step(s, c.frames.back(), c.frames.front());
    INFO("wrap step " << wrap << " m, largest in-cycle step " << largest << " m");
    CHECK(wrap <= 1.2 * largest);
  }
}

TEST_CASE("walking from clips follows straight and curved paths with planted feet at any speed") {
  const auto dir = test::shared_data("bandai-namco-1");
  if (dir.empty()) return;
  for (Sex sex : {Sex::kFemale, Sex::kMale}) {
    const BodyShape s = make_procedural_body({sex, sex == Sex::kMale ? 1.80 : 1.60, 1.0});
    const std::vector<WalkCycle> cycles =
        cycles_for(dir, s, {"dataset-1_walk_normal_001.bvh", "dataset-1_walk_tired_001.bvh"});
    const double fps = 30.0;
    for (double v : {0.6, 1.0, 1.3, 1.7}) {
      const AgentTrajectory t = line_at(v, test::kSanitized ? 3.0 : 5.0, fps);
      const WalkResult w = animate_walking_from_clips(s, cycles, t, fps, 0.3);
      const FootSkate skate = measure_foot_skate(s, w.frames, w.contact);
      INFO("speed " << v << ": skate " << skate.max_m << " m over " << skate.intervals << " stances, IK "
                    << w.max_ik_error_m);
      CHECK(skate.max_m <= 0.01);
      CHECK(skate.intervals >= 3);
      CHECK(w.max_ik_error_m < 1e-6);
      for (size_t f = 0; f < w.frames.size(); ++f) {
        validate_pose(w.frames[f], "walk");
        const Vec3 r = w.frames[f].root_position_m;
        CHECK((Vec2(r.x(), r.z()) - t.position_m[f]).norm() < 0.12);  // on the path, up to sway
        CHECK(std::abs(anim::wrap_angle(w.frames[f].heading_rad())) < 0.5);
      }
    }
    const AgentTrajectory curve = arc(1.1, 2.5, test::kSanitized ? 3.0 : 6.0, fps);
    const WalkResult w = animate_walking_from_clips(s, cycles, curve, fps, 0.0);
    CHECK(measure_foot_skate(s, w.frames, w.contact).max_m <= 0.01);
    for (size_t f = 0; f < w.frames.size(); f += 15)
      CHECK(std::abs(anim::wrap_angle(w.frames[f].heading_rad() - curve.heading_rad[f])) < 0.5);
  }
}

TEST_CASE("walking from clips: stopping keeps both feet down and still - deterministic") {
  const auto dir = test::shared_data("bandai-namco-1");
  if (dir.empty()) return;
  const BodyShape s = make_procedural_body({Sex::kMale, 1.75, 1.0});
  const std::vector<WalkCycle> cycles = cycles_for(dir, s, {"dataset-1_walk_normal_001.bvh"});
  AgentTrajectory t;
  double z = 0;
  for (int k = 0; k < 150; ++k) {
    z += (k < 60 ? 1.2 : 0.0) / 30.0;
    t.position_m.emplace_back(0.0, z);
    t.heading_rad.push_back(0.0);
  }
  const WalkResult a = animate_walking_from_clips(s, cycles, t, 30.0, 0.5);
  const WalkResult b = animate_walking_from_clips(s, cycles, t, 30.0, 0.5);
  CHECK(measure_foot_skate(s, a.frames, a.contact).max_m <= 0.01);
  for (size_t f = 120; f < 150; ++f) CHECK((a.contact[0][f] && a.contact[1][f]));
  for (size_t f = 0; f < a.frames.size(); ++f) {
    CHECK(a.frames[f].root_position_m == b.frames[f].root_position_m);
    CHECK(a.frames[f].local_rotations[kLeftKnee].coeffs() == b.frames[f].local_rotations[kLeftKnee].coeffs());
  }
}

TEST_CASE("a walking crowd from the spec's walk clips - errors name the clip") {
  const auto dir = test::shared_data("bandai-namco-1");
  if (dir.empty()) return;
  AnimationSpec spec;
  spec.motion = MotionSource::clips;
  spec.walk_clips = {"dataset-1_walk_normal_001.bvh", "dataset-1_walk_happy_001.bvh"};
  spec.walk_clip_speeds_mps = {1.2, 1.4};
  AnimationContext ctx;
  ctx.seed = 4;
  ctx.scenario = ScenarioKind::corridor;
  ctx.clip_directory = dir;
  CrowdTrajectories t;
  t.fps = 30;
  t.agents = {line_at(1.1, 2.0, 30.0), line_at(1.4, 2.0, 30.0)};
  const CrowdAnimation crowd = animate_crowd(t, Environment{}, spec, ctx);
  CHECK_NOTHROW(validate_crowd(crowd, "walk clips"));
  CHECK(crowd.characters[1].frames.back().root_position_m.z() > 2.0);
  // A clip that does not walk: no gait cycle, and the message names the file.
  const auto scratch = test::scratch_dir("walk-clips");
  {
    std::ofstream out(scratch / "stand.bvh");
    out << "HIERARCHY\nROOT Hips\n{\n OFFSET 0 0 0\n CHANNELS 6 Xposition Yposition Zposition Zrotation "
           "Xrotation Yrotation\n End Site\n {\n  OFFSET 0 10 0\n }\n}\nMOTION\nFrames: 3\nFrame Time: 0.1\n"
           "0 90 0 0 0 0\n0 90 0 0 0 0\n0 90 0 0 0 0\n";
  }
  spec.walk_clips = {(scratch / "stand.bvh").string()};
  try {
    (void)animate_crowd(t, Environment{}, spec, ctx);
    FAIL("expected InputError");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("stand.bvh") != std::string::npos);
  }
  spec.walk_clips.clear();
  CHECK_THROWS_AS(animate_crowd(t, Environment{}, spec, ctx), InputError);
}

}  // namespace test_walk_clips
