// Social forces and cost-gradient agents: walls, passing, the collision dial, determinism across
// thread counts for every model.
#include <catch2/catch.hpp>
#include <map>
#include <string>
#include <vector>

#include "framework/core/error.hpp"
#include "framework/crowd/cost_gradient_model.hpp"
#include "framework/crowd/disc_collision_events.hpp"
#include "framework/crowd/make_navigation_model.hpp"
#include "framework/crowd/simulate_trajectories.hpp"
#include "framework/crowd/social_force_model.hpp"
#include "tests/crowd/crowd_test_helpers.hpp"
#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_models {

using namespace crowdlab;

namespace {

/// Agents in a 2 m wide corridor (walls x = +-1), some started near a wall, some aiming into one.
std::vector<AgentInit> corridor_agents() {
  std::vector<AgentInit> a;
  for (int i = 0; i < 12; ++i) {
    AgentInit g;
    g.position = Vec2(-0.7 + 0.14 * (i % 11), -3.0 - 0.7 * i);
    g.goal = Vec2(i % 2 ? 3.0 : -3.0, 30.0);  // goals outside the corridor: pulled toward the walls
    g.radius_m = 0.25;
    g.preferred_speed_mps = 1.3;
    g.max_speed_mps = 1.7;
    a.push_back(g);
  }
  return a;
}

const std::vector<ObstacleSegment> kWalls = {{Vec2(-1.0, -20.0), Vec2(-1.0, 40.0)},
                                             {Vec2(1.0, -20.0), Vec2(1.0, 40.0)}};

}  // namespace

TEST_CASE("social forces: agents keep off the walls", "[crowd][social]") {
  CrowdSimulation sim(std::make_shared<SocialForceModel>(SocialForceParams{}), corridor_agents(), kWalls,
                      0.1);
  CHECK(sim.substeps() == 10);  // 0.1 s split into 0.01 s steps for the stiff contact terms
  double closest = 1e9;
  for (int s = 0; s < 150; ++s) {
    sim.step();
    for (std::size_t i = 0; i < sim.size(); ++i)
      closest = std::min(closest, 1.0 - std::fabs(sim.position(i).x()));
  }
  INFO("closest centre-to-wall distance " << closest);
  // Pressed against a wall by the driving force, the exponential wall term balances at
  // d = r - B ln(m v0 / (tau A)) ~ r + 0.01 m: never through the wall, barely touching it.
  CHECK(closest >= 0.25 - 0.02);
  for (std::size_t i = 0; i < sim.size(); ++i) CHECK(std::fabs(sim.position(i).x()) < 1.0);
}

TEST_CASE("social forces: two walkers pass each other without deep overlap", "[crowd][social]") {
  std::vector<AgentInit> a(2);
  a[0].position = {-0.05, -5.0}, a[0].goal = {-0.05, 5.0};
  a[1].position = {0.05, 5.0}, a[1].goal = {0.05, -5.0};
  for (auto& g : a) g.radius_m = 0.25, g.preferred_speed_mps = 1.3, g.max_speed_mps = 1.7;
  CrowdSimulation sim(std::make_shared<SocialForceModel>(SocialForceParams{}), a, {}, 0.1);
  double worst = -1;
  for (int s = 0; s < 150; ++s) {
    sim.step();
    worst = std::max(worst, test::deepest_overlap(sim));
  }
  CHECK(worst < 0.05);
  CHECK(sim.position(0).y() > 4.0);
  CHECK(sim.position(1).y() < -4.0);
}

TEST_CASE("cost-gradient: the separation weight dials residual collisions", "[crowd][cost]") {
  // Two interleaved counter-flows meeting head on (seed 001's scenario B in miniature).
  std::vector<AgentInit> a;
  for (int g = 0; g < 2; ++g)
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 5; ++c) {
        AgentInit x;
        const double dir = g == 0 ? 1.0 : -1.0;
        x.position = Vec2(-1.2 + 0.6 * c + 0.3 * g, -dir * (1.0 + 0.7 * r));
        x.goal = Vec2(x.position.x(), dir * 40.0);
        x.radius_m = 0.25;
        x.preferred_speed_mps = 1.3;
        a.push_back(x);
      }
  auto collisions = [&](double separation) {
    CrowdSpec spec;
    spec.model = CrowdModel::cost;
    spec.cost_weights = {{"separation", separation}};
    CrowdSimulation sim(make_navigation_model(spec), a, {}, 0.1);
    const auto t = simulate_trajectories(sim, 8.0, 10.0, std::vector<double>(a.size(), 0.0),
                                         std::vector<int>(a.size(), 0));
    return disc_collision_events(t).size();
  };
  const std::size_t many = collisions(0.02), few = collisions(3.0);
  INFO("collisions with w_sep 0.02: " << many << ", with 3.0: " << few);
  CHECK(many > few);
  CHECK(many >= 10);
}

TEST_CASE("cost-gradient: head-on walkers sidestep at the closest approach instead of braking",
          "[crowd][cost]") {
  // Nearly head-on (lateral offset 0.1 m, combined radius 0.5 m). The separation cost is taken at the
  // predicted closest approach (seed 001 eqs. 2-3), so its gradient is lateral and both step aside
  // early; a cost at a fixed look-ahead only brakes them and they collide.
  for (const auto& weights : std::vector<std::map<std::string, double>>{
           {}, {{"separation", 1.0}, {"sigma_m", 0.3}, {"lookahead_s", 2.0}}}) {
    for (double offset : {0.1, -0.1, 0.3}) {
      std::vector<AgentInit> a(2);
      a[0].position = {-0.5 * offset, -6.0}, a[0].goal = {-0.5 * offset, 60.0};
      a[1].position = {0.5 * offset, 6.0}, a[1].goal = {0.5 * offset, -60.0};
      for (auto& g : a) g.radius_m = 0.25, g.preferred_speed_mps = 1.3, g.max_speed_mps = 1.7;
      CrowdSpec spec;
      spec.model = CrowdModel::cost;
      spec.cost_weights = weights;
      CrowdSimulation sim(make_navigation_model(spec), a, {}, 0.1);
      double worst = -1;
      for (int s = 0; s < 100; ++s) {
        sim.step();
        worst = std::max(worst, test::deepest_overlap(sim));
      }
      INFO("weights " << weights.size() << " offset " << offset << " deepest overlap " << worst);
      CHECK(worst < 0.05);
      CHECK(sim.position(0).y() > 5.0);  // passed, not stuck
      CHECK(sim.position(1).y() < -5.0);
    }
  }
}

TEST_CASE("cost-gradient: weights are validated by name", "[crowd][cost]") {
  CHECK_THROWS_WITH(cost_gradient_params_from_weights({{"separatoin", 1.0}}),
                    Catch::Contains("crowd.cost_weights.separatoin") && Catch::Contains("unknown"));
  CHECK_THROWS_AS(CostGradientModel(cost_gradient_params_from_weights({{"sigma_m", -1.0}})), InputError);
  CHECK_THROWS_AS(CostGradientModel(cost_gradient_params_from_weights({{"goal", 0.0}, {"smoothness", 0.0}})),
                  InputError);
  CHECK(cost_gradient_params_from_weights({{"goal", 2.5}}).goal == 2.5);
}

TEST_CASE("navigation: identical trajectories with 1 and 2 threads for every model", "[crowd][determinism]") {
  const int n = test::kSanitized ? 300 : 1200;  // several TBB chunks of 256 agents
  for (const CrowdModel model : {CrowdModel::orca, CrowdModel::social, CrowdModel::cost}) {
    CrowdSpec spec;
    spec.model = model;
    auto run = [&](int threads) {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                static_cast<std::size_t>(threads));
      CrowdSimulation sim(make_navigation_model(spec), test::antipodal_circle(n, 0.6, 0.25), kWalls, 0.1);
      sim.set_preferred_velocity_jitter(0.01, 7);
      const auto t =
          simulate_trajectories(sim, model == CrowdModel::social ? 0.6 : 3.0, 10.0,
                                std::vector<double>(sim.size(), 0.0), std::vector<int>(sim.size(), 0));
      return test::trajectories_hash(t);
    };
    INFO("model " << kind_name(model));
    CHECK(run(1) == run(2));
  }
}

}  // namespace test_models
