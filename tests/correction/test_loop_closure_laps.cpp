// The laps after a looping clip's recorded one (issue 28, session 19; loop_closure_laps.hpp): the next lap
// recorded whole in the clip's place, the world-space seam that compares two closed laps, and the rule
// that keeps an extra lap.
#include <tbb/global_control.h>
#include <catch2/catch.hpp>

#include "framework/core/progress.hpp"
#include "framework/correction/correct_crowd.hpp"
#include "framework/correction/corrector.hpp"
#include "framework/correction/loop_closure_laps.hpp"
#include "framework/correction/swaying_crowd_fixture.hpp"
#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_loop_closure_laps {

using namespace crowdlab;

namespace {

/// A dense swaying crowd of `frames` frames.
CrowdAnimation swaying(int characters, int frames, double amplitude, std::uint64_t seed) {
  SwayingCrowdOptions o;
  o.characters = characters;
  o.density_per_m2 = 6.66;
  o.frames = frames;
  o.sway_amplitude = amplitude;
  o.seed = seed;
  return make_swaying_crowd_fixture(o);
}

/// Bit-identical poses (the same steps of the same corrector).
bool same(const Pose& a, const Pose& b) {
  if (a.root_position_m != b.root_position_m) return false;
  for (size_t j = 0; j < a.local_rotations.size(); ++j)
    if (a.local_rotations[j].coeffs() != b.local_rotations[j].coeffs()) return false;
  return true;
}

}  // namespace

TEST_CASE("loop closure laps: the next lap recorded whole is the corrector's next lap",
          "[correction][loop]") {
  const CrowdAnimation crowd = swaying(test::kSanitized ? 4 : 6, 24, 2.0, 3);
  const int window = 8, frames = crowd.frame_count();
  std::vector<BodyShape> shapes;
  for (const CharacterAnimation& c : crowd.characters) shapes.push_back(c.shape);
  Corrector corrector(shapes, CorrectorParams{}, crowd.environment, crowd.meta.fps);
  std::vector<Pose> targets(crowd.characters.size());
  for (int f = 0; f < frames; ++f) {  // the clip
    frame_targets(crowd, f, targets);
    corrector.step(targets);
  }
  // The reference: the same corrector stepped on over one more lap, and over the first frame after it.
  Corrector on = corrector;
  std::vector<std::vector<Pose>> lap(static_cast<size_t>(frames));
  for (int f = 0; f < frames; ++f) {
    frame_targets(crowd, f, targets);
    lap[static_cast<size_t>(f)] = on.step(targets);
  }
  frame_targets(crowd, 0, targets);
  const std::vector<Pose> after_lap = on.step(targets);

  NextLap next(corrector, crowd, window, nullptr);
  const std::vector<std::vector<Pose>> start = next.first(5);  // the closure read its start first
  CHECK(next.stepped() == 5);
  CHECK(start[0].size() == 5);
  RecordedLap recorded = std::move(next).record();
  REQUIRE(recorded.clip.frame_count() == frames);
  for (size_t c = 0; c < crowd.characters.size(); ++c) {
    CHECK(recorded.clip.characters[c].name == crowd.characters[c].name);
    for (int f = 0; f < frames; ++f) {
      CHECK(same(recorded.clip.characters[c].frames[static_cast<size_t>(f)], lap[static_cast<size_t>(f)][c]));
    }
  }
  // The corrector before frame N - W continues into the lap's last W frames; the one after it, into the
  // next lap's first frame.
  REQUIRE(recorded.before_window.has_value());
  for (int f = frames - window; f < frames; ++f) {
    frame_targets(crowd, f, targets);
    const std::vector<Pose> again = recorded.before_window->step(targets);
    CHECK(same(again[0], lap[static_cast<size_t>(f)][0]));
  }
  frame_targets(crowd, 0, targets);
  CHECK(same(recorded.after.step(targets)[1], after_lap[1]));
  CHECK(recorded.contacts_mean >= 0.0);
}

TEST_CASE("loop closure laps: the world seam is the last-to-first step over the median step",
          "[correction][loop]") {
  CrowdAnimation there_and_back = swaying(4, 30, 3.0, 5);
  for (CharacterAnimation& c : there_and_back.characters) {
    const std::vector<Pose> forward = c.frames;
    c.frames.insert(c.frames.end(), forward.rbegin() + 1, forward.rend() - 1);  // ends on frame 1's pose
  }
  // The last frame is frame 1's pose, so the step back to frame 0 is an ordinary step of the sway.
  const double looping = world_seam_step_ratio(there_and_back);
  INFO("there and back: " << looping);
  CHECK(looping > 0.5);
  CHECK(looping < 2.0);
  // Half a sway cut off: the crowd jumps back at the seam.
  const CrowdAnimation one_way = swaying(4, 30, 3.0, 5);
  INFO("one way: " << world_seam_step_ratio(one_way));
  CHECK(world_seam_step_ratio(one_way) > 3.0 * looping);
  // Without motion, or with too few frames, there is no ratio.
  CHECK(world_seam_step_ratio(swaying(4, 30, 0.0, 5)) == 0.0);
  CHECK(world_seam_step_ratio(swaying(4, 2, 3.0, 5)) == 0.0);
}

TEST_CASE("loop closure laps: an extra lap is kept for a smaller seam without deeper contacts",
          "[correction][loop]") {
  const double floor_m = 0.010;
  const ClosedLap first{1.88, 0.0100, 3};
  // Session 19's seed-1 laps: smaller seams, but deeper (16.5 and 13.4 mm against 10.0): not kept.
  CHECK_FALSE(keep_extra_lap(first, {1.30, 0.0165, 2}, floor_m));
  CHECK_FALSE(keep_extra_lap(first, {1.49, 0.0134, 3}, floor_m));
  // As deep, or shallower, and a smaller seam: kept; a larger or equal seam: not.
  CHECK(keep_extra_lap(first, {1.30, 0.0100, 2}, floor_m));
  CHECK(keep_extra_lap(first, {1.30, 0.0060, 2}, floor_m));
  CHECK_FALSE(keep_extra_lap(first, {1.88, 0.0060, 0}, floor_m));
  CHECK_FALSE(keep_extra_lap(first, {2.10, 0.0060, 0}, floor_m));
  // A shallow kept lap: the extra one may reach the depth any closure may reach, no further.
  const ClosedLap shallow{1.90, 0.0040, 1};
  CHECK(keep_extra_lap(shallow, {1.40, 0.0095, 1}, floor_m));
  CHECK_FALSE(keep_extra_lap(shallow, {1.40, 0.0105, 1}, floor_m));
}

TEST_CASE("loop closure laps: a closure that leaves a character open records the next lap too",
          "[correction][loop]") {
  // Nine characters swaying at 4x the fixture's amplitude (seed 4), a 0.5 s closing window: the
  // per-character closure leaves one character open (seeds 1-6 at 2x and 3x close everyone: no extra lap).
  const CrowdAnimation crowd = swaying(9, 60, 4.0, 4);
  CorrectorParams params;
  params.loop_preroll_s = 0.5;
  CorrectionReport report;
  CrowdAnimation one, two;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = correct_crowd(crowd, params, nullptr, &report);
  }
  INFO("closure: " << report.loop_closure << "; open " << report.loop_open_characters);
  CHECK(report.loop_open_characters > 0);
  CHECK(report.extra_laps == 1);  // main: no lap after the first is recorded
  // The kept lap: the first (four lead laps) or the extra one (five).
  CHECK((report.preroll_frames == 4 * 60 || report.preroll_frames == 5 * 60));
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    two = correct_crowd(crowd, params);
  }
  for (size_t c = 0; c < one.characters.size(); ++c)
    for (size_t f = 0; f < one.characters[c].frames.size(); ++f)
      CHECK(same(one.characters[c].frames[f], two.characters[c].frames[f]));
}

TEST_CASE("loop closure laps: the progress counts the extra lap and ends at its total",
          "[correction][loop]") {
  // Session 20 (issue 28): the extra lap's steps were not counted, so `crowdlab correct` showed 100 % and
  // then stalled for a whole lap (minutes on a 20 s clip) before writing its output. Every step is counted
  // now: the total grows by the extra lap's F + W once it is known, what is reported never goes past the
  // total or backwards, and the last report is the total, which every advance summed reaches exactly (no
  // step clamped away). The crowd of the test above: its closure leaves a character open (an extra lap);
  // at 2x amplitude (seed 1) everyone closes (none).
  Progress::set_enabled(false);
  for (const double amplitude : {4.0, 2.0}) {
    const CrowdAnimation crowd = swaying(9, 60, amplitude, amplitude == 4.0 ? 4 : 1);
    CorrectorParams params;
    params.loop_preroll_s = 0.5;
    const int frames = 60, window = 15;  // W: 0.5 s at the fixture's 30 fps
    const std::size_t counted = correction_steps(crowd, params);
    CHECK(counted == static_cast<std::size_t>(5 * frames + window + 2 * window));
    std::vector<ProgressUpdate> seen;
    CorrectionReport report;
    {
      Progress progress("correcting", counted);
      progress.set_observer([&](const ProgressUpdate& u) { seen.push_back(u); });
      correct_crowd(crowd, params, &progress, &report);
    }
    INFO("amplitude " << amplitude << ", closure: " << report.loop_closure << "; extra laps "
                      << report.extra_laps);
    REQUIRE(!seen.empty());
    std::size_t advanced = 0, grown = 0, steps = 0;
    for (size_t k = 0; k < seen.size(); ++k) {
      advanced += seen[k].units;
      if (seen[k].units == 1) ++steps;
      CHECK(seen[k].done <= seen[k].total);
      CHECK(seen[k].done == std::min(advanced, seen[k].total));
      if (k == 0) continue;
      CHECK(seen[k].done >= seen[k - 1].done);
      CHECK(seen[k].total >= seen[k - 1].total);
      if (seen[k].total > seen[k - 1].total) {
        ++grown;
        CHECK(seen[k].total - seen[k - 1].total == static_cast<std::size_t>(frames + window));
        CHECK(seen[k].done < seen[k].total);  // announced while the lap is still to run
      }
    }
    CHECK(grown == static_cast<std::size_t>(report.extra_laps));
    CHECK(advanced == seen.back().total);  // nothing advanced past the total (main: one lap clamped away)
    CHECK(seen.back().done == seen.back().total);
    CHECK(seen.back().total == counted + grown * static_cast<std::size_t>(frames + window));
    // The steps really taken, one advance each: the laps, the recorded one and every closure's window;
    // only the next laps' frames never read are counted done together.
    CHECK(steps >=
          static_cast<std::size_t>((5 + report.extra_laps) * frames + (1 + report.extra_laps) * window));
    if (amplitude == 4.0) CHECK(report.extra_laps == 1);
    if (amplitude == 2.0) CHECK(report.extra_laps == 0);
  }
}

}  // namespace test_loop_closure_laps
