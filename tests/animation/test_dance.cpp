// Dancing and idling: 16 motions, planted feet, seamless loops, variation between neighbours.
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <set>

#include "framework/animation/dance_animation.hpp"
#include "framework/animation/dance_motions.hpp"
#include "framework/animation/foot_skate.hpp"
#include "framework/core/forward_kinematics.hpp"
#include "framework/core/seed.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_dance {

using namespace crowdlab;

namespace {
AgentTrajectory standing(double x, double z, double heading, int frames) {
  AgentTrajectory t;
  t.position_m.assign(static_cast<size_t>(frames), Vec2(x, z));
  t.heading_rad.assign(static_cast<size_t>(frames), heading);
  return t;
}

// Largest joint displacement (m) between two poses of the same body.
double pose_jump(const BodyShape& s, const Pose& a, const Pose& b) {
  const auto pa = joint_positions(s, a), pb = joint_positions(s, b);
  double worst = 0;
  for (size_t j = 0; j < pa.size(); ++j) worst = std::max(worst, (pa[j] - pb[j]).norm());
  return worst;
}
}  // namespace

TEST_CASE("at least 15 distinct dance/idle motions, each periodic in its loop") {
  const auto& motions = dance_motions();
  REQUIRE(motions.size() >= 15);
  std::set<std::string_view> names;
  for (const DanceMotion& m : motions) {
    names.insert(m.name);
    for (double b = 0; b < m.loop_beats; b += 0.37) {
      const DancePose p0 = m.evaluate(b, 1.0), p1 = m.evaluate(b + m.loop_beats, 1.0);
      CHECK((p0.pelvis_offset - p1.pelvis_offset).norm() < 1e-9);
      CHECK(p0.arm[0].raise == Approx(p1.arm[0].raise).margin(1e-9));
      CHECK(p0.foot[1].lift == Approx(p1.foot[1].lift).margin(1e-9));
    }
  }
  CHECK(names.size() == motions.size());
  // Distinct: every pair differs somewhere over the loop.
  for (size_t i = 0; i < motions.size(); ++i)
    for (size_t j = i + 1; j < motions.size(); ++j) {
      double diff = 0;
      for (double b = 0; b < 8; b += 0.25) {
        const DancePose a = motions[i].evaluate(b, 1.0), c = motions[j].evaluate(b, 1.0);
        diff = std::max(
            {diff, std::abs(a.arm[0].raise - c.arm[0].raise), std::abs(a.arm[1].raise - c.arm[1].raise),
             std::abs(a.head_pitch - c.head_pitch), (a.pelvis_offset - c.pelvis_offset).norm() * 10,
             std::abs(a.spine_roll - c.spine_roll), std::abs(a.foot[0].lift - c.foot[0].lift) * 10});
      }
      INFO(motions[i].name << " vs " << motions[j].name);
      CHECK(diff > 0.05);
    }
}

TEST_CASE("every dance motion: planted feet do not skate, IK reaches, feet above ground") {
  const BodyShape s = make_procedural_body({Sex::kFemale, 1.62, 1.0});
  for (int m = 0; m < static_cast<int>(dance_motions().size()); ++m) {
    DanceStyle st;
    st.motion = m;
    st.tempo_bpm = 120;
    st.amplitude = 1.25;
    const DanceResult r = animate_dancing(s, standing(1.0, 2.0, 0.3, 150), 30.0, st);
    const FootSkate skate = measure_foot_skate(s, r.frames, r.contact);
    INFO(dance_motions()[static_cast<size_t>(m)].name << " skate " << skate.max_m);
    CHECK(skate.max_m <= 0.01);
    CHECK(r.max_ik_error_m < 1e-6);
    double lowest = 1e9;
    for (const Pose& p : r.frames)
      for (const Vec3& j : joint_positions(s, p)) lowest = std::min(lowest, j.y());
    CHECK(lowest > -0.005);
  }
}

TEST_CASE("dance loops are seamless: the seam jump is like any other frame-to-frame step") {
  const BodyShape s = make_procedural_body({Sex::kMale, 1.76, 1.0});
  const double fps = 30, duration = 8.0;
  const int frames = static_cast<int>(duration * fps);
  for (int m = 0; m < static_cast<int>(dance_motions().size()); ++m) {
    DanceStyle st = dance_style_from_seed(derive_seed(99, std::to_string(m)), duration);
    st.motion = m;
    st = DanceStyle{m, st.tempo_bpm, st.phase_beats, st.amplitude, st.mirror};
    // Fit whole loops into the clip for this motion.
    const double period = dance_loop_period_s(st);
    st.tempo_bpm *= period / (duration / std::max(1.0, std::round(duration / period)));
    const DanceResult r = animate_dancing(s, standing(0, 0, 0, frames), fps, st);
    double typical = 0, worst_step = 0;
    for (int f = 1; f < frames; ++f) {
      const double d = pose_jump(s, r.frames[static_cast<size_t>(f - 1)], r.frames[static_cast<size_t>(f)]);
      typical += d / (frames - 1);
      worst_step = std::max(worst_step, d);
    }
    const double seam = pose_jump(s, r.frames.back(), r.frames.front());
    INFO(dance_motions()[static_cast<size_t>(m)].name << ": seam " << seam << " typical " << typical
                                                      << " max " << worst_step);
    CHECK(seam <= 1.5 * worst_step + 1e-9);
    CHECK(seam <= 3.0 * typical + 0.002);
  }
}

TEST_CASE("neighbours are never in lock-step, dancing is deterministic") {
  const int n = 20, frames = 240;
  // Lock-step = the same joint velocities at the same time. Signal: every joint's velocity
  // relative to the pelvis (all characters face +Z), concatenated.
  std::vector<std::vector<double>> signal(n);
  std::vector<DanceStyle> styles;
  for (int i = 0; i < n; ++i) {
    const BodyShape s = make_procedural_body({i % 2 ? Sex::kMale : Sex::kFemale, 1.6 + 0.01 * i, 1.0});
    const DanceStyle st = dance_style_from_seed(derive_seed(5, "c" + std::to_string(i)), 8.0);
    styles.push_back(st);
    const DanceResult a = animate_dancing(s, standing(0.5 * i, 0, 0, frames), 30, st);
    const DanceResult b = animate_dancing(s, standing(0.5 * i, 0, 0, frames), 30, st);
    std::array<Vec3, kJointCount> prev{};
    for (int f = 0; f < frames; ++f) {
      const auto& pa = a.frames[static_cast<size_t>(f)];
      const auto& pb = b.frames[static_cast<size_t>(f)];
      REQUIRE(pa.root_position_m == pb.root_position_m);
      REQUIRE(pa.local_rotations[kLeftShoulder].coeffs() == pb.local_rotations[kLeftShoulder].coeffs());
      auto jp = joint_positions(s, pa);
      for (auto& p : jp) p -= pa.root_position_m;
      if (f > 0)
        for (size_t j = 0; j < jp.size(); ++j)
          for (int c = 0; c < 3; ++c) signal[static_cast<size_t>(i)].push_back(jp[j][c] - prev[j][c]);
      prev = jp;
    }
  }
  for (int i = 0; i + 1 < n; ++i) {  // neighbours in a row
    const auto& x = signal[static_cast<size_t>(i)];
    const auto& y = signal[static_cast<size_t>(i + 1)];
    double sxy = 0, sxx = 0, syy = 0;
    for (size_t k = 0; k < x.size(); ++k) sxy += x[k] * y[k], sxx += x[k] * x[k], syy += y[k] * y[k];
    const double corr = sxy / std::sqrt(sxx * syy + 1e-30);
    INFO("neighbours " << i << "," << i + 1 << " velocity correlation " << corr << " motions "
                       << styles[static_cast<size_t>(i)].motion << ","
                       << styles[static_cast<size_t>(i + 1)].motion);
    CHECK(corr < 0.9);
  }
}

TEST_CASE("jumping leaves the ground with both feet, idle motions keep both feet down") {
  const BodyShape s = make_procedural_body({Sex::kMale, 1.8, 1.0});
  int jump = -1, idle = -1;
  for (size_t m = 0; m < dance_motions().size(); ++m) {
    if (dance_motions()[m].name == "jump") jump = static_cast<int>(m);
    if (dance_motions()[m].name == "idle_weight_shift") idle = static_cast<int>(m);
  }
  REQUIRE(jump >= 0);
  REQUIRE(idle >= 0);
  const DanceResult j = animate_dancing(s, standing(0, 0, 0, 120), 30, DanceStyle{jump, 120, 0, 1, false});
  int airborne = 0;
  for (size_t f = 0; f < j.frames.size(); ++f) airborne += (!j.contact[0][f] && !j.contact[1][f]) ? 1 : 0;
  CHECK(airborne > 10);
  const DanceResult i = animate_dancing(s, standing(0, 0, 0, 120), 30, DanceStyle{idle, 60, 0, 1, false});
  for (size_t f = 0; f < i.frames.size(); ++f) CHECK((i.contact[0][f] && i.contact[1][f]));
}

}  // namespace test_dance
