// Quality of the collision correction on small stationary crowds (issue 5 quality targets), measured
// with test-only code (correction_measures.hpp), not the solver's own contact lists.
#include <catch2/catch.hpp>

#include "framework/animation/animate_crowd.hpp"
#include "framework/correction/correct_crowd.hpp"
#include "framework/correction/damping_experiment.hpp"
#include "framework/correction/swaying_crowd_fixture.hpp"
#include "framework/crowd/generate_scenario.hpp"
#include "framework/metrics/correction_quality.hpp"
#include "framework/metrics/measure_crowd.hpp"
#include "framework/pipeline/body_model.hpp"
#include "framework/spec/load_experiment_spec.hpp"
#include "tests/correction/correction_measures.hpp"
#include "tests/correction/corridor_walkers.hpp"
#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_correction_quality {

using namespace crowdlab;

namespace {

struct Quality {
  double overlap_in = 0, overlap_out = 0, p99_depth = 0, mean_dev_deg = 0, skate_m = 0, max_speed = 0;
  CorrectionReport report;
};

Quality measure(int characters, double density, int frames, std::uint64_t seed) {
  SwayingCrowdOptions o;
  o.characters = characters;
  o.density_per_m2 = density;
  o.frames = frames;
  o.seed = seed;
  const CrowdAnimation in = make_swaying_crowd_fixture(o);
  Quality q;
  const CrowdAnimation out = correct_crowd(in, CorrectorParams{}, nullptr, &q.report);
  // The second half of the clip: the first frames start from the input's own interpenetrations.
  for (int f = frames / 2; f < frames; f += 8) {
    q.overlap_in += test::overlap_volume(test::frame_capsules(in, f), 0.03);
    q.overlap_out += test::overlap_volume(test::frame_capsules(out, f), 0.03);
  }
  const CorrectionQuality late = measure_correction_quality(in, out, frames / 2, 2);
  const CorrectionQuality all = measure_correction_quality(in, out, 0, 4);
  q.p99_depth = late.depth_p99_m;
  q.mean_dev_deg = late.rotation_dev_mean_deg;
  q.skate_m = all.foot_skate_max_m;
  q.max_speed = all.joint_speed_max_mps;
  return q;
}

using test::corridor_walkers;

/// The corridor length of the MPFB2-body corridor tests: the spec's 6 m in Release; 3 m (half the
/// characters, at the same density) under the sanitizers, where the corrector runs about 20 times slower
/// and these three tests took 624 s on the full corridor (the foot-budget test alone 407 s, the longest
/// test of the sanitizer run; issue 31). The sanitizer run looks for memory and undefined-behaviour
/// errors, which the same code shows on 20-60 characters; the Release run keeps the full corridor for
/// the numbers. Each check below held on the 3 m corridor when it was chosen (the Release build run with
/// that length: densest corridor 60 characters, p99 depth 8.3 mm, drift p99 7.2 mm; sparsest corridor 20
/// characters, every check passed).
double mpfb2_corridor_length_m() {
  return test::kSanitized ? 3.0 : 0.0;
}

/// The quality measures the MPFB2-corridor tests check, without the mesh-level ones (rendered vertices
/// inside another character, proxy coverage; tests/metrics checks those): no check here reads them, and
/// on these dressed bodies they were most of each test's time (issue 31).
CorrectionQuality capsule_quality(const CrowdAnimation& in, const CrowdAnimation& out) {
  return measure_correction_quality(in, out, 0, 1, false);
}

}  // namespace

TEST_CASE("correction: dense stationary crowd: overlap -95 %, deviation <= 10 deg, skate <= 1 cm",
          "[correction]") {
  const int n = test::kSanitized ? 9 : 16, frames = test::kSanitized ? 24 : 48;
  for (std::uint64_t seed : {2u}) {
    const Quality q = measure(n, 6.66, frames, seed);
    INFO("seed " << seed << ": overlap " << q.overlap_in << " -> " << q.overlap_out << " m^3, p99 depth "
                 << q.p99_depth << " m, mean deviation " << q.mean_dev_deg << " deg, skate " << q.skate_m
                 << " m, contacts " << q.report.contacts_mean << ", CG " << q.report.cg_iterations_mean);
    REQUIRE(q.overlap_in > 0.01);  // the input really is interpenetrating
    CHECK(q.overlap_out <= 0.05 * q.overlap_in);
    CHECK(q.mean_dev_deg <= 10.0);
    CHECK(q.skate_m <= 0.01);
    // Issue target 1 cm, on a fixture whose targets overlap by ~5 L per character (4x the real dancing
    // scenario). Measured 5.0 mm (the depenetration tolerance); 3.0 mm with the pass off.
    CHECK(q.p99_depth <= 0.01);
    CHECK(q.report.rejected_steps == 0);
  }
}

TEST_CASE("correction: moderately dense crowd: overlap removed, shallow residual contacts", "[correction]") {
  const int n = test::kSanitized ? 9 : 16, frames = test::kSanitized ? 24 : 48;
  const Quality q = measure(n, 3.33, frames, 3);
  INFO("overlap " << q.overlap_in << " -> " << q.overlap_out << ", p99 depth " << q.p99_depth
                  << ", deviation " << q.mean_dev_deg << " deg, skate " << q.skate_m);
  REQUIRE(q.overlap_in > 0.0);
  CHECK(q.overlap_out <= 0.05 * q.overlap_in);
  CHECK(q.p99_depth <= 0.01);  // issue target 1 cm (measured 0: no residual contact at all)
  CHECK(q.skate_m <= 0.01);
}

TEST_CASE("correction: a sparse crowd without contact is reproduced within 0.5 deg", "[correction]") {
  SwayingCrowdOptions o;
  o.characters = test::kSanitized ? 4 : 9;
  o.density_per_m2 = 0.25;  // 2 m apart: no contact
  o.frames = test::kSanitized ? 20 : 60;
  const CrowdAnimation in = make_swaying_crowd_fixture(o);
  CorrectionReport report;
  const CrowdAnimation out = correct_crowd(in, CorrectorParams{}, nullptr, &report);
  const double worst = test::max_rotation_deviation_deg(in, out);
  const CorrectionQuality quality = measure_correction_quality(in, out);
  const double mean = quality.rotation_dev_mean_deg, p99 = quality.rotation_dev_p99_deg;
  INFO("max deviation " << worst << " deg, p99 " << p99 << " deg, mean " << mean << " deg");
  CHECK(p99 <= 0.5);  // issue target 0.5 deg: measured p99 0.32 deg, mean 0.03 deg
  CHECK(mean <= 0.1);
  CHECK(worst <= 1.0);  // the worst joint (a light hand under fast sway) lags by ~0.66 deg
  double root_err = 0.0;
  for (size_t c = 0; c < in.characters.size(); ++c)
    for (size_t f = 0; f < in.characters[c].frames.size(); ++f)
      root_err = std::max(
          root_err,
          (in.characters[c].frames[f].root_position_m - out.characters[c].frames[f].root_position_m).norm());
  CHECK(root_err <= 0.005);
}

TEST_CASE("correction: no explosion over many steps (bounded velocities)", "[correction]") {
  SwayingCrowdOptions o;
  o.characters = test::kSanitized ? 6 : 12;
  o.density_per_m2 = 6.66;
  o.frames = test::kSanitized ? 60 : 600;
  const CrowdAnimation in = make_swaying_crowd_fixture(o);
  CorrectionReport report;
  const CrowdAnimation out = correct_crowd(in, CorrectorParams{}, nullptr, &report);
  double max_speed = 0.0;
  for (size_t c = 0; c < out.characters.size(); ++c)
    for (size_t f = 1; f < out.characters[c].frames.size(); ++f) {
      const auto a = joint_positions(out.characters[c].shape, out.characters[c].frames[f - 1]);
      const auto b = joint_positions(out.characters[c].shape, out.characters[c].frames[f]);
      for (int j = 0; j < kJointCount; ++j)
        max_speed =
            std::max(max_speed, (b[static_cast<size_t>(j)] - a[static_cast<size_t>(j)]).norm() * o.fps);
    }
  INFO("max joint speed " << max_speed << " m/s over " << o.frames << " steps");
  CHECK(report.rejected_steps == 0);
  CHECK(max_speed < 20.0);  // bounded (an explosion grows without bound); measured ~10 m/s at a hand
}

TEST_CASE("correction: damping experiment (seed 000 Fig. 4): d = 0 rings, d = 0.006 recovers, d = 0.6 drifts",
          "[correction]") {
  // Full length: the recovery needs the 4.5 s after the push.
  const auto runs = run_damping_experiment({0.0, 0.006, 0.6}, CorrectorParams{}, 8.0);
  REQUIRE(runs.size() == 3);
  for (const auto& r : runs) {
    INFO("d = " << r.damping << ": rms " << r.rms_deviation_m << " m, max " << r.max_deviation_m
                << " m, overshoot " << r.overshoot_m << " m, last second " << r.final_deviation_m << " m");
    CHECK(r.max_deviation_m > 0.003);  // the push really moved the character (d = 0.6 resists: ~4 mm)
    CHECK(r.time_s.size() == r.position_m.size());
    // Before the push the character stands on its target (the pusher starts out of reach).
    for (size_t i = 0; i < r.time_s.size() && r.time_s[i] < 2.9; ++i)
      CHECK(std::abs(r.position_m[i] - r.target_m[i]) < 0.005);
  }
  const auto &none = runs[0], &paper = runs[1], &heavy = runs[2];
  CHECK(none.overshoot_m > 2.0 * paper.overshoot_m);               // without damping it rings
  CHECK(heavy.final_deviation_m > 3.0 * paper.final_deviation_m);  // heavy damping drifts
  CHECK(paper.final_deviation_m < 0.002);                          // d = 0.006 is back on target
}

TEST_CASE("correction: planted feet of a walking corridor crowd stay put (skate <= 1 cm)", "[correction]") {
  // Without foot holds the correction slid planted feet by ~15 cm here.
  const CrowdAnimation in = corridor_walkers(test::kSanitized ? 1.0 : 3.0);
  CorrectorParams params;
  params.settle_steps = 30;
  const CrowdAnimation out = correct_crowd(in, params);
  const CorrectionQuality q = measure_correction_quality(in, out);
  const double overlap_in = measure_crowd(in).mean_character_overlap_l;
  const double overlap_out = measure_crowd(out).mean_character_overlap_l;
  INFO(in.characters.size() << " characters, " << in.frame_count() << " frames: skate " << q.foot_skate_max_m
                            << " m, overlap " << overlap_in << " -> " << overlap_out << " L, deviation "
                            << q.rotation_dev_mean_deg << " deg, p99 depth " << q.depth_p99_m << " m");
  REQUIRE(overlap_in > 0.0);  // the input's legs really do interpenetrate
  CHECK(q.foot_skate_max_m <= 0.01);
  // >= 95 % removed on the 3 s clip (measured 96 %); the sanitizer build's 1 s clip is still in the
  // start-up transient (measured 94 %), so it is held to 90 %.
  CHECK(overlap_out <= (test::kSanitized ? 0.10 : 0.05) * overlap_in);
  CHECK(q.rotation_dev_mean_deg <= 10.0);
  CHECK(q.depth_p99_m <= 0.01);  // issue target 1 cm; measured 4.9 mm
}

TEST_CASE("correction: the depenetration pass removes the deep contacts the Newton step leaves",
          "[correction]") {
  // gomez2024's corridor at its lowest density, with the pass off and on: the one Newton step alone
  // leaves legs centimetres inside each other (stage_depenetrate.cpp); the pass brings the p99 depth
  // under the 1 cm without sliding planted feet or adding deviation.
  const CrowdAnimation in = corridor_walkers(test::kSanitized ? 1.0 : 2.0);
  CorrectorParams off;
  off.depenetration_passes = 0;
  const CorrectionQuality without = measure_correction_quality(in, correct_crowd(in, off));
  const CorrectionQuality with = measure_correction_quality(in, correct_crowd(in, CorrectorParams{}));
  INFO("p99 depth " << without.depth_p99_m << " -> " << with.depth_p99_m << " m, max " << without.depth_max_m
                    << " -> " << with.depth_max_m << " m, deviation " << without.rotation_dev_mean_deg
                    << " -> " << with.rotation_dev_mean_deg << " deg, skate " << without.foot_skate_max_m
                    << " -> " << with.foot_skate_max_m << " m");
  CHECK(without.depth_p99_m > 0.01);  // the step alone misses the target here
  CHECK(with.depth_p99_m <= 0.01);
  CHECK(with.depth_max_m < without.depth_max_m);
  CHECK(with.rotation_dev_mean_deg <= without.rotation_dev_mean_deg + 0.5);
  CHECK(with.foot_skate_max_m <= 0.01);
}

TEST_CASE("correction: planted feet stay at the input's height, so bodies do not float", "[correction]") {
  // gomez2024's sparsest corridor on its MPFB2 bodies, where the correction barely has to move anyone.
  // With planted feet held horizontally only (height left to the solve), whole bodies rose on their
  // planted feet: measured on a 1 s clip of this condition, pelvis 20 mm above the input's (median), the
  // soles of planted feet 101 mm above the input's (p99). Held at the input's height: 5 mm and 39 mm.
  const CrowdAnimation in =
      corridor_walkers(test::kSanitized ? 1.0 : 2.0, false, true, mpfb2_corridor_length_m());
  const CrowdAnimation out = correct_crowd(in, CorrectorParams{});
  const CorrectionQuality q = capsule_quality(in, out);
  std::vector<double> lift;  // pelvis height above the input's, every character and frame
  for (size_t c = 0; c < in.characters.size(); ++c)
    for (int f = 0; f < in.frame_count(); ++f)
      lift.push_back(out.characters[c].frames[static_cast<size_t>(f)].root_position_m.y() -
                     in.characters[c].frames[static_cast<size_t>(f)].root_position_m.y());
  const double median_lift = nearest_rank_quantile(lift, 0.5);
  INFO("pelvis lift median " << median_lift << " m, planted-foot float p99 " << q.feet.float_p99_m
                             << " m (max " << q.feet.float_max_m << "), feet below ground max "
                             << q.feet.ground_penetration_max_m << " m, drift p99 "
                             << q.feet.stance_drift_p99_m);
  CHECK(std::abs(median_lift) <= 0.01);
  // Issue 27: held feet return their tilt to the input's and the depenetration pass may not lift them
  // (measured on the 2 s clip: 26.9 -> 16.0 mm; the sanitizer build's 1 s clip keeps the old bound).
  CHECK(q.feet.float_p99_m <= (test::kSanitized ? 0.06 : 0.021));
  CHECK(q.feet.stance_drift_p99_m <= 0.01);
}

TEST_CASE("correction: the foot motion budget stops feet jumping in the densest corridor", "[correction]") {
  // gomez2024's corridor at 6.66 /m^2 on its MPFB2 bodies: without the budget the depenetration pass
  // threw feet 5-20 cm farther than their input moved in one frame. Measured on this 2 s clip with
  // planted feet held horizontally only: 12 -> 2 foot pops, worst excess 20.7 -> 6.8 cm, p99 depth 5.0
  // -> 5.7 mm, deviation 7.3 -> 7.2 deg; with planted feet also held at the input's height and the
  // budget rows prioritised (issue 18): 10 -> 0 pops, worst excess 7.3 -> 2.6 cm, p99 depth 5.8 -> 6.7
  // mm, deviation 7.8 -> 7.6 deg.
  const CrowdAnimation in =
      corridor_walkers(test::kSanitized ? 1.0 : 2.0, true, true, mpfb2_corridor_length_m());
  REQUIRE(in.characters.size() >= (test::kSanitized ? 50u : 100u));
  const CorrectionQuality with = capsule_quality(in, correct_crowd(in, CorrectorParams{}));
  INFO("with the budget: foot pops " << with.feet.foot_pops << ", worst excess " << with.feet.pop_excess_max_m
                                     << " m, drift p99 " << with.feet.stance_drift_p99_m << " m, p99 depth "
                                     << with.depth_p99_m << " m, deviation " << with.rotation_dev_mean_deg
                                     << " deg");
  // The comparison without the budget runs in the Release build only: the sanitizer build's 1 s clip may
  // have no pop to remove, and this one solve of 100+ characters took 6 of its 12 minutes there.
  if (!test::kSanitized) {
    CorrectorParams off;
    off.foot_pop_budget_m = 0.0;
    const CorrectionQuality without = capsule_quality(in, correct_crowd(in, off));
    INFO("without the budget: foot pops " << without.feet.foot_pops << ", worst excess "
                                          << without.feet.pop_excess_max_m << " m");
    CHECK(without.feet.foot_pops >= 8);
    CHECK(with.feet.foot_pops == 0);
    CHECK(with.feet.pop_excess_max_m < without.feet.pop_excess_max_m);
  }
  CHECK(with.feet.pop_excess_max_m < 0.05);
  CHECK(with.feet.stance_drift_p99_m <= 0.01);
  CHECK(with.depth_p99_m <= 0.01);
  CHECK(with.rotation_dev_mean_deg <= 10.0);
}

TEST_CASE("correction: joints that touch nobody keep their input, and no joint flips", "[correction]") {
  // Issue 27: gomez2024's sparsest corridor on its MPFB2 bodies, where most limbs touch nobody. Before
  // the free-joint release (release_free_joints = false, the session-8 solver) joints 10 cm from
  // everyone for +-0.5 s deviated from their input by up to ~20 deg (3 s clip: p99 5.9, max 20.6 deg)
  // and light joints flipped (350 joint-frames turning > 20 deg within 3 frames; 401 on this 2 s clip).
  const CrowdAnimation in =
      corridor_walkers(test::kSanitized ? 1.0 : 2.0, false, true, mpfb2_corridor_length_m());
  CorrectorParams off;
  off.release_free_joints = false;
  const CorrectionQuality without = capsule_quality(in, correct_crowd(in, off));
  const CorrectionQuality with = capsule_quality(in, correct_crowd(in, CorrectorParams{}));
  INFO("free-limb deviation p99 / max "
       << without.free_limbs.p99_deg << " / " << without.free_limbs.max_deg << " -> "
       << with.free_limbs.p99_deg << " / " << with.free_limbs.max_deg << " deg over "
       << with.free_limbs.free_joint_frames << " joint-frames; flips " << without.flips.count << " -> "
       << with.flips.count << "; p99 depth " << without.depth_p99_m << " -> " << with.depth_p99_m);
  REQUIRE(with.free_limbs.free_joint_frames > 1000);
  // The old solver edits free limbs visibly (6.7 deg max on the 2 s clip with the dressed bodies; 4.5 deg on
  // the sanitizer build's 1 s clip), and at least three times as much as the release leaves (1.5 deg).
  CHECK(without.free_limbs.max_deg > 2.0);
  CHECK(without.free_limbs.max_deg > 3.0 * with.free_limbs.max_deg);
  CHECK(without.flips.count > 0);
  CHECK(with.free_limbs.p99_deg <= 2.0);
  CHECK(with.free_limbs.max_deg <= 5.0);
  // Issue 27's target is 0; measured 401 -> 9 on this clip (knees and re-planted feet are not limited).
  CHECK(with.flips.count * 20 <= without.flips.count);
  CHECK(with.depth_p99_m <= 0.01);
}

}  // namespace test_correction_quality
