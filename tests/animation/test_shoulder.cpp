// Shoulder reactions: ttca/dtca triggering on hand-built pairs, sides, probability, forced counts.
#include <catch2/catch.hpp>
#include <cmath>

#include "framework/animation/shoulder_reactions.hpp"
#include "framework/core/closest_approach.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_shoulder {

using namespace crowdlab;

namespace {
// Two agents on parallel lines x = +-d/2 walking toward each other along z at speed v, meeting at
// t_meet. Agent 0 walks +Z from z < 0, agent 1 walks -Z.
CrowdTrajectories pair(double d, double v, double t_meet, double fps, double seconds) {
  CrowdTrajectories t;
  t.fps = fps;
  t.agents.resize(2);
  const int n = static_cast<int>(seconds * fps);
  for (int k = 0; k < n; ++k) {
    const double time = k / fps;
    t.agents[0].position_m.emplace_back(-d / 2, v * (time - t_meet));
    t.agents[0].heading_rad.push_back(0.0);
    t.agents[1].position_m.emplace_back(d / 2, -v * (time - t_meet));
    t.agents[1].heading_rad.push_back(3.14159265358979323846);
  }
  return t;
}
}  // namespace

TEST_CASE("reactions trigger exactly on the first frame with 0 <= ttca < 0.7 s and dtca < 0.6 m") {
  const double fps = 30, v = 1.3, t_meet = 3.01;  // trigger boundary between frames
  for (double d : {0.2, 0.35, 0.5, 0.59}) {
    const CrowdTrajectories t = pair(d, v, t_meet, fps, 6.0);
    const ShoulderReactions r = compute_shoulder_reactions(t, {}, 1);
    REQUIRE(r.events.size() == 2);
    // Analytic: ttca(t) = t_meet - t (relative speed 2v along z), dtca = d.
    const int expected =
        static_cast<int>(std::floor((t_meet - 0.7) * fps)) + 1;  // first frame with ttca < 0.7
    for (const ShoulderEvent& e : r.events) {
      CHECK(e.frame == expected);
      CHECK(e.dtca_m == Approx(d).margin(1e-9));
      CHECK(e.reacted);
    }
    // Weights: zero before the trigger, non-zero after, peak at the closest approach.
    for (size_t a = 0; a < 2; ++a) {
      for (int f = 0; f < expected; ++f) CHECK(r.weight[a][static_cast<size_t>(f)] == 0.0);
      CHECK(std::abs(r.weight[a][static_cast<size_t>(expected + 1)]) > 0.0);
      CHECK(std::abs(r.weight[a][static_cast<size_t>(std::lround(t_meet * fps))]) ==
            Approx(1.0).margin(0.02));
      CHECK(r.weight[a].back() == 0.0);  // blended out again
    }
  }
  // Just outside the distance threshold: nothing.
  const ShoulderReactions none = compute_shoulder_reactions(pair(0.61, v, t_meet, fps, 6.0), {}, 1);
  CHECK(none.events.empty());
  for (const auto& w : none.weight)
    for (double x : w) CHECK(x == 0.0);
}

TEST_CASE("the torso turns toward the side of passing") {
  // Agent 0 walks +Z at x = -d/2 with agent 1 at x = +d/2: agent 1 passes on agent 0's left (+X).
  const ShoulderReactions r = compute_shoulder_reactions(pair(0.4, 1.2, 2.5, 30, 5.0), {}, 3);
  REQUIRE(r.events.size() == 2);
  CHECK(r.events[0].agent == 0);
  CHECK(r.events[0].side == 1);
  CHECK(r.weight[0][75] > 0.9);
  // Agent 1 faces -Z, so its left is world -X, where agent 0 walks.
  CHECK(r.events[1].side == 1);
  CHECK(r.weight[1][75] > 0.9);
}

TEST_CASE("agents moving apart or standing still never trigger") {
  CrowdTrajectories t = pair(0.3, 1.2, -1.0, 30, 3.0);  // met before the clip started: separating
  CHECK(compute_shoulder_reactions(t, {}, 1).events.empty());
  for (auto& a : t.agents)
    for (auto& p : a.position_m) p = a.position_m.front();
  CHECK(compute_shoulder_reactions(t, {}, 1).events.empty());
}

TEST_CASE("risks on both sides: react to the earliest closest approach") {
  // Agent 0 walks +Z; agent 1 passes on its right (closest at 2.35 s) before agent 2 passes on its
  // left (2.5 s).
  CrowdTrajectories t;
  t.fps = 30;
  t.agents.resize(3);
  for (int k = 0; k < 150; ++k) {
    const double time = k / 30.0;
    t.agents[0].position_m.emplace_back(0.0, 1.2 * (time - 2.5));
    t.agents[0].heading_rad.push_back(0.0);
    t.agents[1].position_m.emplace_back(-0.4, -1.2 * (time - 2.2));
    t.agents[1].heading_rad.push_back(3.14159);
    t.agents[2].position_m.emplace_back(0.4, -1.2 * (time - 2.5));
    t.agents[2].heading_rad.push_back(3.14159);
  }
  const ShoulderReactions r = compute_shoulder_reactions(t, {}, 4);
  int reacted_side = 0;
  for (const ShoulderEvent& e : r.events)
    if (e.agent == 0 && e.reacted) {
      reacted_side = e.side;
      CHECK(e.partner == 1);
    }
  CHECK(reacted_side == -1);
  CHECK(r.weight[0][71] < -0.99);  // at the first closest approach, turned to the right
}

TEST_CASE("trigger probability: 0 never, 1 always, 0.5 about half of many events") {
  const CrowdTrajectories t = pair(0.3, 1.3, 2.0, 30, 4.0);
  ShoulderReactionParams p;
  p.trigger_probability = 0.0;
  for (const auto& e : compute_shoulder_reactions(t, p, 1).events) CHECK_FALSE(e.reacted);
  p.trigger_probability = 1.0;
  for (const auto& e : compute_shoulder_reactions(t, p, 1).events) CHECK(e.reacted);
  p.trigger_probability = 0.5;
  int reacted = 0, total = 0;
  for (std::uint64_t seed = 0; seed < 400; ++seed)
    for (const auto& e : compute_shoulder_reactions(t, p, seed).events) reacted += e.reacted ? 1 : 0, ++total;
  CHECK(total == 800);
  CHECK(reacted == Approx(400).margin(60));  // binomial(800, 0.5): SD 14
  p.trigger_probability = 1.5;
  CHECK_THROWS(compute_shoulder_reactions(t, p, 1));
}

TEST_CASE(
    "pair experiment: shoulder factor 0/1/2 makes exactly that many characters react, at any distance") {
  for (double d : {0.2, 0.45, 0.7}) {
    for (int count : {0, 1, 2}) {
      ShoulderReactionParams p;
      p.forced_count = count;
      p.trigger_probability = 0.0;
      const ShoulderReactions r = compute_shoulder_reactions(pair(d, 1.3, 2.0, 30, 4.0), p, 17);
      int reacting = 0;
      for (const auto& w : r.weight) {
        double peak = 0;
        for (double x : w) peak = std::max(peak, std::abs(x));
        reacting += peak > 0.9 ? 1 : 0;
      }
      INFO("distance " << d << " count " << count);
      CHECK(reacting == count);
    }
  }
}

}  // namespace test_shoulder
