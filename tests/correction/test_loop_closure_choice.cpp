// Which loop closure each character takes (framework/correction/loop_closure_choice.hpp; issue 28, session
// 15): the descent alone left open neighbours that can close only together, and a start from the next lap;
// session 16: the join checks each candidate over the frames it changes, and joints cut from the next lap;
// session 17: the join on an excerpt of the clip (loop_closure_excerpt.hpp); session 18: why a character
// stays open (explain_open_characters).
#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "framework/core/forward_kinematics.hpp"
#include "framework/core/joint_flips.hpp"
#include "framework/correction/blend_keeping_planted_feet.hpp"
#include "framework/correction/loop_closure_choice.hpp"
#include "framework/correction/loop_closure_excerpt.hpp"
#include "framework/correction/swaying_crowd_fixture.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_loop_closure_choice {

using namespace crowdlab;

namespace {

/// Three swaying characters A, B, C standing far apart (x = 0, 2, 6 m) in the unclosed clip.
CrowdAnimation three_far_apart(int frames = 40) {
  SwayingCrowdOptions o;
  o.characters = 3;
  o.frames = frames;
  CrowdAnimation crowd = make_swaying_crowd_fixture(o);
  const std::array<double, 3> x = {0.0, 2.0, 6.0};
  for (size_t c = 0; c < 3; ++c)
    for (Pose& p : crowd.characters[c].frames) {
      p.root_position_m.x() = x[c];
      p.root_position_m.z() = 0.0;
    }
  return crowd;
}

/// The flip window's frames at 30 fps (core/joint_flips.hpp): the excerpt's margin on both sides of its join.
const int kFlipFrames30 = flip_window(30.0).frames;

/// `crowd` with character c moved to x_m on frames [first, N): a closure of its window.
void move_window(CrowdAnimation& crowd, size_t c, int first, double x_m) {
  for (size_t f = static_cast<size_t>(first); f < crowd.characters[c].frames.size(); ++f)
    crowd.characters[c].frames[f].root_position_m.x() = x_m;
}

/// Another lap's poses: the clip's frames [first, first + count) of every character with every joint
/// turned by 0.5 rad about x.
std::vector<std::vector<Pose>> turned_lap(const CrowdAnimation& clip, int first, int count) {
  std::vector<std::vector<Pose>> lap(clip.characters.size());
  const Quat turn(Eigen::AngleAxisd(0.5, Vec3::UnitX()));
  for (size_t c = 0; c < lap.size(); ++c)
    for (int k = 0; k < count; ++k) {
      Pose p = clip.characters[c].frames[static_cast<size_t>(first + k)];
      for (Quat& q : p.local_rotations) q = turn * q;
      lap[c].push_back(p);
    }
  return lap;
}

}  // namespace

TEST_CASE("loop closure choice: neighbours that can close only together close together",
          "[correction][loop]") {
  // The closure candidate moves A onto B's unclosed place (x = 2), B onto A's (x = 0) and C onto x = 2 too.
  // Together A and B are apart on it; each alone meets the other's unclosed body; C meets A there. The
  // descent (all on the candidate, every too-deep character moved on at once) opens A and C, then B (it
  // now meets A's unclosed body): all three open, as before session 15. The join then closes A and B
  // together; C cannot close (it would meet A, now closed) and stays open.
  const CrowdAnimation unclosed = three_far_apart();
  const int first = 20;
  CrowdAnimation closed = unclosed;
  move_window(closed, 0, first, 2.0);
  move_window(closed, 1, first, 0.0);
  move_window(closed, 2, first, 2.0);
  const double limit_m = 0.01;
  const std::vector<const CrowdAnimation*> closures = {&closed};
  const std::vector<std::vector<bool>> any = {{true, true, true}};
  const std::vector<size_t> choice = choose_closures(closures, 1, unclosed, first, 0, limit_m, any);
  REQUIRE(choice.size() == 3);
  CHECK(choice[0] == 0);  // A closed
  CHECK(choice[1] == 0);  // B closed, with A
  CHECK(choice[2] == 1);  // C unclosed
  // Nobody deeper than the limit in the mixed crowd, on any frame.
  const CrowdAnimation mixed = mix_closures(closures, unclosed, choice);
  for (double d : deepest_per_character(mixed, 0, mixed.frame_count())) CHECK(d <= limit_m);
  CHECK(mixed.characters[0].frames.back().root_position_m.x() == 2.0);
  CHECK(mixed.characters[2].frames.back().root_position_m.x() == 6.0);
  // Where no character meets another, the first candidate is everyone's.
  move_window(closed, 2, first, 6.5);
  const std::vector<size_t> all = choose_closures(closures, 1, unclosed, first, 0, limit_m, any);
  CHECK(all == std::vector<size_t>{0, 0, 0});
  // A candidate not allowed to a character (one that would add joint flips to it) is never its: B stays
  // unclosed, so A, which would meet B's unclosed body, cannot close either; C still can.
  const std::vector<size_t> without_b =
      choose_closures(closures, 1, unclosed, first, 0, limit_m, {{true, false, true}});
  CHECK(without_b == std::vector<size_t>{1, 1, 0});
}

TEST_CASE("loop closure choice: a character whose arm is open at the seam starts from the next lap",
          "[correction][loop]") {
  // One swaying character, played forward then back (it loops), whose clip ends with its left arm raised
  // 40 degrees off its first frame's (an open arm at the seam); next_start is what follows that end: the
  // clip's first frames with the arm still raised, as a next lap would begin from the raised arm.
  SwayingCrowdOptions o;
  o.characters = 1;
  o.frames = 30;
  CrowdAnimation clip = make_swaying_crowd_fixture(o);
  std::vector<Pose>& frames = clip.characters[0].frames;  // forward then back: the input loops
  const std::vector<Pose> forward = frames;
  frames.insert(frames.end(), forward.rbegin(), forward.rend());
  const CrowdAnimation input = clip;
  const Quat raise(Eigen::AngleAxisd(40.0 * std::numbers::pi / 180.0, Vec3::UnitZ()));
  const size_t shoulder = static_cast<size_t>(kLeftShoulder);
  Pose& last = clip.characters[0].frames.back();
  last.local_rotations[shoulder] = raise * last.local_rotations[shoulder];
  const int window = 20;
  std::vector<std::vector<Pose>> next_start(1);
  for (int k = 0; k < window; ++k) {
    Pose p = clip.characters[0].frames[static_cast<size_t>(k)];
    p.local_rotations[shoulder] = raise * p.local_rotations[shoulder];
    next_start[0].push_back(p);
  }
  auto seam_m = [](const CrowdAnimation& a) {
    const CharacterAnimation& c = a.characters[0];
    const auto p = joint_positions(c.shape, c.frames.back()), q = joint_positions(c.shape, c.frames.front());
    return (p[static_cast<size_t>(kLeftHand)] - q[static_cast<size_t>(kLeftHand)]).norm();
  };
  const CrowdAnimation started = start_from_next_lap(input, next_start, CorrectorParams{}, clip);
  INFO("left hand's seam step: " << seam_m(clip) << " m open, " << seam_m(started) << " m started");
  CHECK(seam_m(clip) > 0.1);
  // Frame 0 is now next_start's first pose, one ordinary step after the raised last frame.
  const Pose& f0 = started.characters[0].frames.front();
  CHECK(f0.local_rotations[shoulder].angularDistance(next_start[0][0].local_rotations[shoulder]) < 1e-9);
  CHECK(seam_m(started) < 0.2 * seam_m(clip));
  // The blend fades out over the window: from frame W on the clip is its own, its end untouched.
  for (size_t f = window; f < clip.characters[0].frames.size(); ++f)
    CHECK(started.characters[0].frames[f].local_rotations[shoulder].angularDistance(
              clip.characters[0].frames[f].local_rotations[shoulder]) < 1e-12);
  // Half-way through the window the arm is between the two (raised cosine).
  const double mid = started.characters[0].frames[window / 2].local_rotations[shoulder].angularDistance(
      clip.characters[0].frames[window / 2].local_rotations[shoulder]);
  CHECK(mid > 0.2 * 40.0 * std::numbers::pi / 180.0);
  CHECK(mid < 0.8 * 40.0 * std::numbers::pi / 180.0);
}

TEST_CASE("loop closure choice: close_joints brings only the named joints to the lap's end",
          "[correction][loop]") {
  SwayingCrowdOptions o;
  o.characters = 2;
  o.frames = 30;
  const CrowdAnimation clip = make_swaying_crowd_fixture(o);
  const int window = 10, first = 20;
  const std::vector<std::vector<Pose>> lap_end = turned_lap(clip, first, window);
  const CrowdAnimation closed = close_joints(clip, lap_end, kRightArmJoints);
  for (size_t c = 0; c < 2; ++c) {
    const Pose& end = closed.characters[c].frames.back();
    for (int j = 0; j < kJointCount; ++j) {
      const bool right_arm =
          std::find(kRightArmJoints.begin(), kRightArmJoints.end(), j) != kRightArmJoints.end();
      const Quat& want = (right_arm ? lap_end[c].back() : clip.characters[c].frames.back())
                             .local_rotations[static_cast<size_t>(j)];
      CHECK(end.local_rotations[static_cast<size_t>(j)].angularDistance(want) < 1e-9);
    }
    for (size_t f = 0; f < static_cast<size_t>(first); ++f)  // before the window, nothing changes
      for (size_t j = 0; j < static_cast<size_t>(kJointCount); ++j)
        CHECK(closed.characters[c].frames[f].local_rotations[j].coeffs() ==
              clip.characters[c].frames[f].local_rotations[j].coeffs());
  }
}

TEST_CASE("loop closure choice: the join checks a candidate over the frames it changes",
          "[correction][loop]") {
  // Candidate 0 moves A onto B (x = 2) on frames [5, 15), inside the clip, far from the closure's window
  // [30, 40); candidate 1 moves A 0.5 m aside on [30, 40), where it meets nobody. Checked over the frames
  // each changes, A takes candidate 1; checked over the window alone (the spans before session 16), it
  // took candidate 0 and went through B mid-clip.
  CrowdAnimation unclosed = three_far_apart();
  const int first = 30;
  CrowdAnimation inside = unclosed, aside = unclosed;
  for (size_t f = 5; f < 15; ++f) inside.characters[0].frames[f].root_position_m.x() = 2.0;
  move_window(aside, 0, first, -0.5);
  const std::vector<const CrowdAnimation*> closures = {&inside, &aside};
  const std::vector<std::vector<bool>> any = {{true, true, true}, {true, true, true}};
  const std::vector<FrameSpan> spans = {{0, 15}, {first, 40}};
  const std::vector<size_t> choice = choose_closures(closures, 0, unclosed, first, 0, 0.01, any, spans);
  REQUIRE(choice.size() == 3);
  CHECK(choice[0] == 1);
  const std::vector<size_t> window_only = choose_closures(closures, 0, unclosed, first, 0, 0.01, any);
  CHECK(window_only[0] == 0);
}

TEST_CASE("loop closure choice: explain_open_characters names the neighbours an open character meets",
          "[correction][loop]") {
  // A (x = 0) is open. Candidate 0 stands it at x = 1.8 on its first 10 frames and its last, next to B
  // (x = 2), which candidate 2 closes; candidate 3 stands A at x = 2.0, deeper into B. Candidates 1 and 2
  // are not A's to take (they would add joint flips to it). The join leaves A open; the explanation says
  // so: 2 candidates excluded, the best of the others candidate 0 (as many met as candidate 3, shallower),
  // where A meets B (and nobody else) beyond the limit.
  const CrowdAnimation unclosed = three_far_apart();
  const auto stand_at = [&](size_t c, double x_m) {
    CrowdAnimation crowd = unclosed;
    for (size_t f : {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 39})
      crowd.characters[c].frames[f].root_position_m.x() = x_m;
    return crowd;
  };
  const CrowdAnimation a_near_b = stand_at(0, 1.8), b_aside = stand_at(1, 2.6), b_closed = stand_at(1, 2.0),
                       a_on_b = stand_at(0, 2.0);
  const std::vector<const CrowdAnimation*> closures = {&a_near_b, &b_aside, &b_closed, &a_on_b};
  const std::vector<FrameSpan> spans(4, {0, 40});
  const std::vector<std::vector<bool>> allowed = {
      {true, false, false}, {false, true, false}, {false, true, false}, {true, false, false}};
  const double limit_m = 0.01;
  const size_t open = closures.size();
  std::vector<size_t> rung = {open, 2, open};
  join_closures(closures, unclosed, limit_m, allowed, spans, rung);
  REQUIRE(rung == std::vector<size_t>{open, 2, open});
  const std::vector<OpenCharacterReason> why =
      explain_open_characters(closures, unclosed, limit_m, allowed, spans, rung);
  REQUIRE(why.size() == 2);  // A and C (C may take no candidate)
  CHECK(why[0].character == 0);
  CHECK(why[0].excluded == 2);
  CHECK(why[0].best == 0);
  REQUIRE(why[0].met.size() == 1);
  CHECK(why[0].met[0].first == 1);
  const CrowdAnimation a_closed = mix_closures(closures, unclosed, {0, 2, open});
  CHECK(why[0].met[0].second == Approx(deepest_per_character(a_closed, 0, 40)[0]));
  CHECK(why[0].met[0].second > limit_m);
  CHECK(why[1].character == 2);
  CHECK(why[1].excluded == 4);
  CHECK(why[1].best == open);
  CHECK(why[1].met.empty());
}

TEST_CASE("loop closure choice: cut_joints_from_next_lap moves the arm's seam inside the clip",
          "[correction][loop]") {
  SwayingCrowdOptions o;
  o.characters = 2;
  o.frames = 30;
  const CrowdAnimation clip = make_swaying_crowd_fixture(o);
  const int cut = 8, window = 10;
  const std::vector<std::vector<Pose>> next_lap = turned_lap(clip, 0, o.frames);  // every joint turned
  const CrowdAnimation mixed = cut_joints_from_next_lap(clip, next_lap, kLeftArmJoints, cut, window);
  const auto elbow = static_cast<size_t>(kLeftElbow), knee = static_cast<size_t>(kLeftKnee);
  for (size_t c = 0; c < 2; ++c) {
    const auto& got = mixed.characters[c].frames;
    const auto& own = clip.characters[c].frames;
    for (size_t f = 0; f < own.size(); ++f) {
      INFO("frame " << f);
      CHECK(got[f].local_rotations[knee].coeffs() == own[f].local_rotations[knee].coeffs());  // not an arm
      CHECK(got[f].root_position_m == own[f].root_position_m);
      const double to_own = got[f].local_rotations[elbow].angularDistance(own[f].local_rotations[elbow]);
      const double to_next =
          got[f].local_rotations[elbow].angularDistance(next_lap[c][f].local_rotations[elbow]);
      if (f < static_cast<size_t>(cut)) CHECK(to_next < 1e-9);  // the next lap's: frame 0 follows frame N-1
      if (f >= static_cast<size_t>(cut + window)) CHECK(to_own < 1e-9);
    }
    // Inside the window the arm turns back gradually: no step larger than the whole turn's third.
    for (int f = cut; f < cut + window; ++f) {
      const auto ff = static_cast<size_t>(f);
      CHECK(got[ff].local_rotations[elbow].angularDistance(got[ff - 1].local_rotations[elbow]) <
            own[ff].local_rotations[elbow].angularDistance(own[ff - 1].local_rotations[elbow]) + 0.5 / 3.0);
    }
  }
  // Session 17: the join's candidates hold only the characters it may move; a character without frames
  // stays so, here and in close_joints, and the others are changed as before.
  CrowdAnimation sparse = clip;
  sparse.characters[0].frames.clear();
  const CrowdAnimation sparse_cut = cut_joints_from_next_lap(sparse, next_lap, kLeftArmJoints, cut, window);
  CHECK(sparse_cut.characters[0].frames.empty());
  CHECK(sparse_cut.characters[1].frames[0].local_rotations[elbow].coeffs() ==
        mixed.characters[1].frames[0].local_rotations[elbow].coeffs());
  const std::vector<std::vector<Pose>> lap_end = turned_lap(clip, o.frames - window, window);
  const CrowdAnimation sparse_closed = close_joints(sparse, lap_end, kLeftArmJoints);
  CHECK(sparse_closed.characters[0].frames.empty());
  CHECK(sparse_closed.characters[1].frames.back().local_rotations[elbow].coeffs() ==
        close_joints(clip, lap_end, kLeftArmJoints)
            .characters[1]
            .frames.back()
            .local_rotations[elbow]
            .coeffs());
}

namespace {

/// `crowd` with character c moved to x_m on frames [begin, end).
void move(CrowdAnimation& crowd, size_t c, int begin, int end, double x_m) {
  for (int f = begin; f < end; ++f)
    crowd.characters[c].frames[static_cast<size_t>(f)].root_position_m.x() = x_m;
}

}  // namespace

TEST_CASE("loop closure excerpt: keeps the first and last frames, or the whole clip where they meet",
          "[correction][loop]") {
  const ClosureExcerpt ex = ClosureExcerpt::of(100, 40, 20, kFlipFrames30);
  CHECK(ex.head == 40 + kFlipFrames30);
  CHECK(ex.tail_begin == 80 - kFlipFrames30);
  CHECK(ex.size() == 60 + 2 * kFlipFrames30);
  CHECK(ex.index(0) == 0);
  CHECK(ex.index(99) == ex.size() - 1);
  CHECK(ex.map({80, 100}).begin == ex.size() - 20);
  CHECK(ex.map({80, 100}).end == ex.size());
  CHECK(ex.map({0, 30}).end == 30);
  // A 4 s clip at W = 60 (head 2W, tail W): nothing to drop, the whole clip.
  const ClosureExcerpt whole = ClosureExcerpt::of(120, 120, 60, kFlipFrames30);
  CHECK(whole.size() == 120);
  CHECK(whole.index(100) == 100);
  // cut and put_back: the kept frames go back where they were, the others stay.
  const CrowdAnimation clip = three_far_apart(100);
  CrowdAnimation cut = ex.cut(clip);
  REQUIRE(cut.frame_count() == ex.size());
  CHECK(cut.characters[1].frames[static_cast<size_t>(ex.index(85))].root_position_m ==
        clip.characters[1].frames[85].root_position_m);
  for (Pose& p : cut.characters[1].frames) p.root_position_m.y() += 1.0;
  CharacterAnimation back = clip.characters[1];
  ex.put_back(cut.characters[1], back);
  CHECK(back.frames[10].root_position_m.y() == clip.characters[1].frames[10].root_position_m.y() + 1.0);
  CHECK(back.frames[60].root_position_m.y() == clip.characters[1].frames[60].root_position_m.y());
  CHECK(back.frames[99].root_position_m.y() == clip.characters[1].frames[99].root_position_m.y() + 1.0);
}

TEST_CASE("loop closure excerpt: the join on the excerpt chooses as on the whole clip",
          "[correction][loop]") {
  // A and B close only together at the end (they swap places on [80, 100)); C meets A there, but a
  // candidate that changes only the clip's first 30 frames (C away from everyone) closes it. The whole
  // choice gives A and B the end closure and C the start one; so must the descent on the whole clip and
  // the join on the excerpt (frames [0, 30 + margin) and [80 - margin, 100): the middle dropped).
  const CrowdAnimation unclosed = three_far_apart(100);
  const int first = 80;
  CrowdAnimation end_closure = unclosed, start_closure = unclosed;
  move(end_closure, 0, first, 100, 2.0);
  move(end_closure, 1, first, 100, 0.0);
  move(end_closure, 2, first, 100, 2.0);
  move(start_closure, 2, 0, 30, 6.5);
  const std::vector<const CrowdAnimation*> closures = {&end_closure, &start_closure};
  const std::vector<FrameSpan> spans = {{first, 100}, {0, 30}};
  const std::vector<std::vector<bool>> any(2, {true, true, true});
  const double limit_m = 0.01;
  const std::vector<size_t> whole = choose_closures(closures, 1, unclosed, first, 0, limit_m, any, spans);
  REQUIRE(whole == std::vector<size_t>{0, 0, 1});

  std::vector<size_t> rung = descend_closures(closures, 1, unclosed, first, 0, limit_m, any);
  const ClosureExcerpt ex = ClosureExcerpt::of(100, 30, 20, kFlipFrames30);
  REQUIRE(ex.size() < 100);
  const std::vector<CrowdAnimation> cut = {ex.cut(end_closure), ex.cut(start_closure)};
  const std::vector<const CrowdAnimation*> cut_closures = {&cut[0], &cut[1]};
  join_closures(cut_closures, ex.cut(unclosed), limit_m, any, {ex.map(spans[0]), ex.map(spans[1])}, rung);
  CHECK(rung == whole);
  // Written back, the chosen excerpt frames give the whole choice's crowd.
  const CrowdAnimation mixed = mix_closures(closures, unclosed, whole);
  CrowdAnimation from_excerpt = unclosed;
  for (size_t c = 0; c < 3; ++c)
    ex.put_back(cut_closures[rung[c]]->characters[c], from_excerpt.characters[c]);
  for (size_t c = 0; c < 3; ++c)
    for (size_t f = 0; f < 100; ++f)
      CHECK(from_excerpt.characters[c].frames[f].root_position_m ==
            mixed.characters[c].frames[f].root_position_m);
}

}  // namespace test_loop_closure_choice
