// Measures on hand-built trajectories with known answers.
#include <catch2/catch.hpp>
#include <cmath>

#include "framework/crowd/collision_table.hpp"
#include "framework/crowd/disc_collision_events.hpp"
#include "framework/crowd/interpersonal_distance_histogram.hpp"
#include "framework/crowd/pair_closest_approaches.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_measures {

using namespace crowdlab;

namespace {
CrowdTrajectories make(int agents, int frames, double fps = 10.0) {
  CrowdTrajectories t;
  t.fps = fps;
  t.agents.resize(static_cast<std::size_t>(agents));
  for (auto& a : t.agents) {
    a.position_m.assign(static_cast<std::size_t>(frames), Vec2::Zero());
    a.heading_rad.assign(static_cast<std::size_t>(frames), 0.0);
    a.radius_m = 0.25;
  }
  return t;
}
}  // namespace

TEST_CASE("measures: a collision is counted when a pair starts overlapping", "[crowd][measures]") {
  // Agent 1 sits at x = d(f) from agent 0: apart, overlapping for frames 10..19, apart, again 30..34.
  auto t = make(3, 50);
  for (int f = 0; f < 50; ++f) {
    const bool touch = (f >= 10 && f < 20) || (f >= 30 && f < 35);
    const double d = touch ? 0.5 - 0.01 * (1 + f % 3) : 0.8;
    t.agents[1].position_m[static_cast<std::size_t>(f)] = Vec2(d, 0.0);
    t.agents[2].position_m[static_cast<std::size_t>(f)] = Vec2(10.0, 0.0);  // never involved
  }
  const auto ev = disc_collision_events(t);
  REQUIRE(ev.size() == 2);
  CHECK(ev[0].i == 0);
  CHECK(ev[0].j == 1);
  CHECK(ev[0].start_frame == 10);
  CHECK(ev[0].end_frame == 20);
  CHECK(ev[0].max_penetration_m == Approx(0.03));
  CHECK(ev[1].start_frame == 30);
  CHECK(ev[1].end_frame == 35);
  // Overlapping from the first frame to the last: one event, open-ended.
  auto s = make(2, 5);
  for (auto& p : s.agents[1].position_m) p = Vec2(0.3, 0.0);
  const auto ev2 = disc_collision_events(s);
  REQUIRE(ev2.size() == 1);
  CHECK(ev2[0].start_frame == 0);
  CHECK(ev2[0].end_frame == 5);
  CHECK(disc_collision_events_csv(ev, 10.0).find("0,1,10,20,1,1,0.03") != std::string::npos);
}

TEST_CASE("measures: ttca and dtca per frame and pair match the analytic crossing", "[crowd][measures]") {
  // Two agents at 1 m/s on parallel lines 0.4 m apart, passing at t = 2 s.
  auto t = make(2, 41, 10.0);
  for (int f = 0; f < 41; ++f) {
    const double time = f / 10.0;
    t.agents[0].position_m[static_cast<std::size_t>(f)] = Vec2(0.0, time - 2.0);
    t.agents[1].position_m[static_cast<std::size_t>(f)] = Vec2(0.4, 2.0 - time);
  }
  const auto rows = pair_closest_approaches(t, 10.0);
  REQUIRE(rows.size() == 41);
  for (const PairApproach& r : rows) {
    CHECK(r.dtca_m == Approx(0.4).margin(1e-9));
    CHECK(r.ttca_s == Approx(2.0 - r.frame / 10.0).margin(1e-9));
  }
  CHECK(rows[20].distance_m == Approx(0.4));
  // A distance limit filters pairs.
  CHECK(pair_closest_approaches(t, 1.0).size() == 9);  // |dz| < 0.9165 m: frames 16..24
  CHECK(pair_closest_approaches_csv(rows, 10.0).rfind("frame,time_s,i,j,distance_m,ttca_s,dtca_m\n", 0) == 0);
}

TEST_CASE("measures: interpersonal distance histogram", "[crowd][measures]") {
  // A static right triangle with legs 0.35 and 0.45 m (hypotenuse 0.570 m).
  auto t = make(3, 4);
  for (int f = 0; f < 4; ++f) {
    t.agents[1].position_m[static_cast<std::size_t>(f)] = Vec2(0.35, 0.0);
    t.agents[2].position_m[static_cast<std::size_t>(f)] = Vec2(0.0, 0.45);
  }
  const auto h = interpersonal_distance_histogram(t, 0.1, 1.0);
  REQUIRE(h.counts.size() == 10);
  CHECK(h.total == 12);
  CHECK(h.counts[3] == 4);
  CHECK(h.counts[4] == 4);
  CHECK(h.counts[5] == 4);
  CHECK(h.mean_m == Approx((0.35 + 0.45 + std::hypot(0.35, 0.45)) / 3.0));
  const auto nn = interpersonal_distance_histogram(t, 0.1, 1.0, true);
  CHECK(nn.total == 12);     // one sample per agent and frame
  CHECK(nn.counts[3] == 8);  // agents 0 and 1: 0.3 m
  CHECK(nn.counts[4] == 4);  // agent 2: 0.4 m
  CHECK_THROWS(interpersonal_distance_histogram(t, 0.0, 1.0));
}

TEST_CASE("measures: collision table in the form of seed 001 Table 2", "[crowd][measures]") {
  std::vector<CollisionCount> c = {{"A", 0.5, 1, 46, 2}, {"A", 0.5, 2, 50, 3},    {"A", 0.5, 3, 54, 4},
                                   {"B", 0.5, 1, 28, 1}, {"A", 2.8, 1, 4546, 90}, {"B", 2.8, 1, 26060, 700}};
  const auto cells = collision_table(c);
  REQUIRE(cells.size() == 4);
  CHECK(cells[0].scenario == "A");
  CHECK(cells[0].density == 0.5);
  CHECK(cells[0].mean == Approx(50.0));
  CHECK(cells[0].sd == Approx(4.0));
  CHECK(cells[1].density == 2.8);
  CHECK(cells[1].sd == 0.0);
  const std::string md = collision_table_markdown(cells);
  CHECK(md.find("| Density | 0.5 | 2.8 |") != std::string::npos);
  CHECK(md.find("| Scenario A | 50 \u00b1 4 | 4546 \u00b1 0 |") != std::string::npos);
  CHECK(collision_table_csv(cells).find("A,0.5,3,50,4,3\n") != std::string::npos);
}

}  // namespace test_measures
