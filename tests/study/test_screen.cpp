// The window's drawing, layout and video source, headless (no display needed): click targets,
// the Next rule, and that the streamed playback gives the clip's frames with bounded memory.
#include <chrono>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <thread>

#include "framework/core/error.hpp"

#include "study_ui/frame_interval_stats.hpp"
#include "study_ui/scale_keys.hpp"
#include "study_ui/trial_screen.hpp"
#include "study_ui/video_source.hpp"
#include "tests/study/study_fixture.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_screen {

using namespace crowdlab;
using namespace crowdlab::study;

TEST_CASE("trial screen layout: targets inside the canvas, disjoint, found by hit_test", "[study]") {
  ProtocolSpec likert, afc;
  afc.type = ProtocolType::two_afc;
  ProtocolSpec eleven;  // 11-point scales in the narrow cells of a 3-column grid
  eleven.type = ProtocolType::rating;
  eleven.questions = {{"A", "a", false, "scale", 11, {}},
                      {"B", "b", false, "scale", 11, {}},
                      {"C", "c", false, "scale", 11, {}},
                      {"D", "d", false, "scale", 11, {}},
                      {"E", "e", false, "scale", 11, {}}};
  for (const auto* p : {&likert, &afc, &eleven})
    for (cv::Size size :
         {cv::Size(1280, 720), cv::Size(1920, 1080), cv::Size(1024, 768), cv::Size(3840, 2160)})
      for (double share : {0.0, 0.3, 0.5, 0.9}) {
        const auto qs = resolve_questions(*p);
        const TrialLayout L = layout_trial_screen(size, qs, share);
        INFO(kind_name(p->type) << " " << size.width << "x" << size.height << " share " << share);
        const cv::Rect canvas({0, 0}, size);
        CHECK((L.video_area & canvas) == L.video_area);
        CHECK(L.video_area.height >= size.height / 5);
        TrialScreenState state;
        state.answers.assign(qs.size(), -1);
        for (size_t i = 0; i < L.targets.size(); ++i) {
          const auto& t = L.targets[i];
          CHECK((t.rect & canvas) == t.rect);
          CHECK((t.rect & L.video_area).area() == 0);
          for (size_t j = i + 1; j < L.targets.size(); ++j) CHECK((t.rect & L.targets[j].rect).area() == 0);
          if (t.question >= 0) CHECK((t.rect & L.cells[static_cast<size_t>(t.question)]) == t.rect);
          const cv::Point centre(t.rect.x + t.rect.width / 2, t.rect.y + t.rect.height / 2);
          const auto hit = hit_test(L, state, centre);
          if (t.question < 0) {
            CHECK_FALSE(hit);  // Next is disabled until every question is answered
          } else {
            REQUIRE(hit);
            CHECK(hit->question == t.question);
            CHECK(hit->value == t.value);
            CHECK(qs[static_cast<size_t>(t.question)].valid(t.value));
          }
        }
        for (size_t q = 0; q < qs.size(); ++q) state.answers[q] = qs[q].min_response();
        CHECK(state.all_answered());
        const cv::Point next(L.next_button.x + 5, L.next_button.y + 5);
        REQUIRE(hit_test(L, state, next));
        CHECK(hit_test(L, state, next)->question == -1);
        state.questions_enabled = false;
        const auto& first = L.targets.front();
        CHECK_FALSE(hit_test(L, state, {first.rect.x + 1, first.rect.y + 1}));
      }
}

TEST_CASE("the video is as large as the questions allow, and video_share sets its share", "[study]") {
  const auto qs = resolve_questions(ProtocolSpec{});  // seed 000's six Likert statements
  REQUIRE(qs.size() == 6);
  const TrialLayout L = layout_trial_screen({1920, 1080}, qs);
  const cv::Rect video = fit_rect({1920, 1080}, L.video_area);
  CHECK(video.width >= 1280);
  CHECK(video.height >= 720);
  for (const cv::Rect& cell : L.cells) CHECK(cell.y >= L.video_area.y + L.video_area.height);
  // Q1/Q2, Q3/Q4 and Q5/Q6 share a column (seed 000's item pairs).
  for (size_t i = 0; i < 6; i += 2) CHECK(L.cells[i].x == L.cells[i + 1].x);
  for (double share : {0.35, 0.5}) {
    const TrialLayout S = layout_trial_screen({1920, 1080}, qs, share);
    CHECK(std::abs(S.video_area.height - share * 1080) <= 2);
    CHECK(S.body_px > L.body_px);  // the questions take the room the video leaves
  }
  // A share larger than the questions allow at their smallest is capped, never overlapping them.
  const TrialLayout big = layout_trial_screen({1280, 720}, qs, 0.9);
  for (const cv::Rect& cell : big.cells) CHECK(cell.y >= big.video_area.y + big.video_area.height);
}

TEST_CASE("fit_rect keeps the aspect ratio and centres", "[study]") {
  const cv::Rect r = fit_rect({1920, 1080}, {10, 20, 1000, 300});
  CHECK(r.height == 300);
  CHECK(r.width == 533);
  CHECK(r.x == 10 + (1000 - 533) / 2);
  CHECK(r.y == 20);
}

TEST_CASE("video source: streamed frames equal the clip's frames, looping, memory bounded by a few frames",
          "[study]") {
  const auto dir = test::scratch_dir("study-video");
  const std::string clip = (dir / "clip.mp4").string();
  test::write_test_clip(clip, 3, 12);
  // The clip decoded directly, scaled as the window shows it.
  std::vector<cv::Mat> expected;
  cv::VideoCapture cap(clip, cv::CAP_FFMPEG);
  for (cv::Mat raw; cap.read(raw);) {
    cv::Mat scaled;
    const cv::Size size = fit_rect(raw.size(), {0, 0, 320, 180}).size();
    cv::resize(raw, scaled, size, 0, 0, scale_interpolation(raw.size(), size));
    expected.push_back(scaled);
  }
  REQUIRE(expected.size() == 12);
  VideoSource looping(clip, {0, 0, 320, 180}, 30.0, true, 3);
  CHECK(looping.fps() == Approx(30.0));
  CHECK(looping.frame_count() == 12);
  for (long k : {0L, 1L, 2L, 5L, 11L, 12L, 13L, 20L, 25L, 25L, 30L, 47L}) {  // skips, a repeat, wraps
    CAPTURE(k);
    const cv::Mat a = looping.frame(k).clone();
    REQUIRE(a.size() == cv::Size(320, 180));
    CHECK(cv::norm(a, expected[static_cast<size_t>(k % 12)], cv::NORM_INF) == 0.0);
  }
  // The decoder stays at most `ahead` frames in front, however long the clip plays.
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  CHECK(looping.frames_buffered() <= 3);
  // Played once: past the end, the last frame stays.
  VideoSource once(clip, {0, 0, 320, 180}, 30.0, false, 3);
  CHECK(cv::norm(once.frame(4), expected[4], cv::NORM_INF) == 0.0);
  CHECK(cv::norm(once.frame(40), expected[11], cv::NORM_INF) == 0.0);
  CHECK(once.frame_count() == 12);
  VideoSource missing((dir / "missing.mp4").string(), {0, 0, 320, 180}, 30.0, true);
  CHECK_THROWS_AS(missing.frame(0), RuntimeError);
}

TEST_CASE("frame interval statistics: mean, nearest-rank p99 and max of consecutive differences", "[study]") {
  CHECK(frame_interval_stats({}).mean_ms < 0);
  CHECK(frame_interval_stats({5.0}).max_ms < 0);
  const auto two = frame_interval_stats({0.0, 40.0});
  CHECK(two.mean_ms == 40.0);
  CHECK(two.p99_ms == 40.0);
  CHECK(two.max_ms == 40.0);
  // 200 intervals: 197 of 33 ms, then 50, 60 and 100 ms. Nearest rank: the 198th of 200 -> 50 ms.
  std::vector<double> t = {0.0};
  for (int i = 0; i < 197; ++i) t.push_back(t.back() + 33.0);
  for (double d : {100.0, 50.0, 60.0}) t.push_back(t.back() + d);
  const auto s = frame_interval_stats(t);
  CHECK(s.mean_ms == Approx((197 * 33.0 + 210.0) / 200.0));
  CHECK(s.p99_ms == 50.0);
  CHECK(s.max_ms == 100.0);
}

TEST_CASE("keyboard answers reach every point of 10- and 11-point scales", "[study]") {
  ProtocolSpec p;
  p.type = ProtocolType::rating;
  p.questions = {{"A", "a", false, "scale", 11, {}},
                 {"B", "b", false, "scale", 10, {}},
                 {"C", "c", false, "scale", 7, {}}};
  const auto qs = resolve_questions(p);
  // Types `keys` (digits, or '.' for any other key) and returns the answers.
  auto type = [&](const std::string& keys) {
    TrialScreenState state;
    state.answers.assign(qs.size(), -1);
    DigitEntry entry;
    for (char c : keys) {
      if (c == '.') {
        entry = {};
        continue;
      }
      if (const auto a = enter_digit(entry, state, qs, c - '0'))
        state.answers[static_cast<size_t>(a->first)] = a->second;
    }
    return state.answers;
  };
  CHECK(type("11107") == std::vector<int>{11, 10, 7});
  CHECK(type("1.17") == std::vector<int>{1, 1, 7});   // another key closes the open 1
  CHECK(type("0101") == std::vector<int>{1, 1, -1});  // 01: an explicit single-digit answer
  CHECK(type("9103") == std::vector<int>{9, 10, 3});
  CHECK(type("1017") == std::vector<int>{10, 1, 7});
  CHECK(type("12") == std::vector<int>{1, 2, -1});   // 12 > 11: the 2 answers the next question
  CHECK(type("5558") == std::vector<int>{5, 5, 5});  // 8 > 7 points: ignored
  for (int v = 1; v <= 11; ++v) {                    // every point of the 11-point scale
    const std::string keys = (v < 10 ? "0" : "") + std::to_string(v);
    CHECK(type(keys)[0] == v);
  }
}

}  // namespace test_screen
