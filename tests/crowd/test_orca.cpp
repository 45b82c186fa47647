// ORCA: the linear programs on analytic cases, collision-free crossings, walls, determinism.
#include <catch2/catch.hpp>
#include <utility>

#include "framework/core/error.hpp"
#include "framework/crowd/orca_linear_program.hpp"
#include "framework/crowd/orca_model.hpp"
#include "tests/crowd/crowd_test_helpers.hpp"
#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_orca {

using namespace crowdlab;

namespace {
OrcaParams default_orca() {
  return OrcaParams{};
}
}  // namespace

TEST_CASE("orca: lp2 projects onto a violated half-plane and respects the speed disc", "[crowd][orca]") {
  // Half-plane v.x >= 1: line through (1, 0) pointing -y (left side is +x).
  orca::Line L{1.0, 0.0, 0.0, -1.0};
  double rx, ry;
  REQUIRE(orca::lp2(&L, 1, 2.0, -1.0, 0.5, false, rx, ry) == 1);
  CHECK(rx == Approx(1.0));
  CHECK(ry == Approx(0.5));
  // Optimum outside the disc: clamped to radius first, then constrained.
  REQUIRE(orca::lp2(&L, 1, 2.0, 0.0, 5.0, false, rx, ry) == 1);
  CHECK(rx == Approx(1.0));
  CHECK(ry == Approx(std::sqrt(3.0)));
  // Line outside the disc: infeasible at index 0.
  orca::Line far{3.0, 0.0, 0.0, -1.0};
  CHECK(orca::lp2(&far, 1, 2.0, 0.0, 0.0, false, rx, ry) == 0);
}

TEST_CASE("orca: lp3 balances infeasible constraints", "[crowd][orca]") {
  // v.x >= 1 and v.x <= -1 cannot both hold: the least worst is v.x = 0 (violation 1 each).
  orca::Line lines[2] = {{1.0, 0.0, 0.0, -1.0}, {-1.0, 0.0, 0.0, 1.0}};
  orca::Line scratch[2];
  double rx = 0, ry = 0;
  const std::size_t failed = orca::lp2(lines, 2, 1.5, 0.3, 0.2, false, rx, ry);
  REQUIRE(failed == 1);
  orca::lp3(lines, 2, 0, failed, 1.5, scratch, rx, ry);
  CHECK(rx == Approx(0.0).margin(1e-9));
  CHECK(std::hypot(rx, ry) <= 1.5 + 1e-9);
}

TEST_CASE("orca: two agents swapping places head-on never overlap", "[crowd][orca]") {
  const auto model = std::make_shared<OrcaModel>(default_orca());
  for (double offset : {0.0, 0.01, 0.2, -0.3}) {
    std::vector<AgentInit> a(2);
    a[0].position = {-5.0, 0.0}, a[0].goal = {5.0, offset};
    a[1].position = {5.0, offset}, a[1].goal = {-5.0, 0.0};
    for (auto& g : a) g.radius_m = 0.25, g.preferred_speed_mps = 1.3, g.max_speed_mps = 1.5;
    CrowdSimulation sim(model, a, {}, 0.1);
    double worst = -1.0;
    for (int s = 0; s < 200; ++s) {
      sim.step();
      worst = std::max(worst, test::deepest_overlap(sim));
    }
    INFO("offset " << offset);
    CHECK(worst <= 0.0);
    CHECK((sim.position(0) - a[0].goal).norm() < 0.05);
    CHECK((sim.position(1) - a[1].goal).norm() < 0.05);
  }
}

namespace {
/// Runs the antipodal circle until everyone arrives; returns (deepest overlap over all steps, arrived).
std::pair<double, bool> run_circle(int n, bool resolve_overlaps, int max_steps) {
  const auto agents = test::antipodal_circle(n, 0.6, 0.25);
  OrcaParams p = default_orca();
  p.resolve_overlaps = resolve_overlaps;
  CrowdSimulation sim(std::make_shared<OrcaModel>(p), agents, {}, 0.1);
  double worst = -1.0;
  bool arrived = false;
  for (int s = 0; s < max_steps && !arrived; ++s) {
    sim.step();
    worst = std::max(worst, test::deepest_overlap(sim));
    arrived = true;
    for (std::size_t i = 0; i < sim.size() && arrived; ++i)
      arrived = (sim.position(i) - agents[i].goal).norm() < 0.05;
  }
  return {worst, arrived};
}
}  // namespace

TEST_CASE("orca: agents on a circle reach their antipodes without overlapping", "[crowd][orca]") {
  // (Rings of fewer than ~100 agents compress into a touching arch and stall: ORCA has no way out.)
  // Overlap-free mode: step guards in the infeasible programs plus the overlap projection.
  const int n = test::kSanitized ? 120 : 250;
  const auto [worst, arrived] = run_circle(n, true, 3000);
  INFO("deepest overlap " << worst << " m");
  CHECK(arrived);
  CHECK(worst <= 1e-3);
}

TEST_CASE("orca: plain ORCA overlaps in the infeasible jam (why the overlap-free mode exists)",
          "[crowd][orca]") {
  // The paper's own caveat (Sec. 5.2): when the programs are infeasible the 3D fallback only
  // minimises the largest violation. Measured: ~0.29 m for 250 agents at dt = 0.1 s.
  if (test::kSanitized) return;
  const auto [worst, arrived] = run_circle(250, false, 3000);
  CHECK(arrived);
  CHECK(worst > 1e-3);
  CHECK(worst < 0.35);
}

TEST_CASE("orca: walls are never crossed and agents slide along them", "[crowd][orca]") {
  // A wall along x = 1 from y = -10 to 10; agents aim through it.
  const std::vector<ObstacleSegment> walls = {{Vec2(1.0, -10.0), Vec2(1.0, 10.0)}};
  std::vector<AgentInit> a(5);
  for (int i = 0; i < 5; ++i) {
    a[static_cast<std::size_t>(i)].position = {-2.0, -2.0 + i};
    a[static_cast<std::size_t>(i)].goal = {4.0, -1.0 + i};
    a[static_cast<std::size_t>(i)].radius_m = 0.25;
  }
  CrowdSimulation sim(std::make_shared<OrcaModel>(default_orca()), a, walls, 0.1);
  double closest = 1e9;
  for (int s = 0; s < 200; ++s) {
    sim.step();
    for (std::size_t i = 0; i < sim.size(); ++i) {
      CHECK(sim.position(i).x() < 1.0);
      closest = std::min(closest, 1.0 - sim.position(i).x());
    }
  }
  CHECK(closest >= 0.25 - 1e-3);
  CHECK(test::deepest_overlap(sim) <= 1e-3);
}

TEST_CASE("orca: out-of-range parameters are rejected", "[crowd][orca]") {
  OrcaParams p;
  p.max_neighbors = 0;
  CHECK_THROWS_AS(OrcaModel(p), InputError);
  p = {};
  p.time_horizon_s = -1;
  CHECK_THROWS_AS(OrcaModel(p), InputError);
  std::vector<AgentInit> a(1);
  a[0].radius_m = -0.1;
  CHECK_THROWS_WITH(CrowdSimulation(std::make_shared<OrcaModel>(OrcaParams{}), a, {}, 0.1),
                    Catch::Contains("radius must be positive"));
}

TEST_CASE("orca: the overlap-free mode gives identical trajectories with 1 and 2 threads",
          "[crowd][orca][determinism]") {
  // 600 agents (several TBB chunks) run into the central jam, where guards and projection act.
  const int n = test::kSanitized ? 300 : 600;
  OrcaParams p = default_orca();
  p.resolve_overlaps = true;
  auto run = [&](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                              static_cast<std::size_t>(threads));
    CrowdSimulation sim(std::make_shared<OrcaModel>(p), test::antipodal_circle(n, 0.6, 0.25), {}, 0.1);
    sim.set_preferred_velocity_jitter(0.01, 11);
    std::vector<double> xy;
    for (int s = 0; s < (test::kSanitized ? 250 : 450); ++s) sim.step();
    for (std::size_t i = 0; i < sim.size(); ++i)
      xy.push_back(sim.position(i).x()), xy.push_back(sim.position(i).y());
    return std::make_pair(xy, sim.overlap_resolutions());
  };
  const auto one = run(1), two = run(2);
  CHECK(one.second > 0);  // the projection did run
  CHECK(one.first == two.first);
  CHECK(one.second == two.second);
}

}  // namespace test_orca
