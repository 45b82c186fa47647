// The papers' scenarios: sizes and densities, geometry, pair-crossing distances, walls, errors,
// determinism.
#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "framework/core/error.hpp"
#include "framework/crowd/count_spec_collisions.hpp"
#include "framework/crowd/generate_scenario.hpp"
#include "framework/spec/type_condition.hpp"
#include "tests/crowd/crowd_test_helpers.hpp"
#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_scenarios {

using namespace crowdlab;

namespace {

FactorLevel level(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return {buf, v};
}

Condition condition(std::map<std::string, FactorLevel> levels, int rep = 1, std::uint64_t seed = 77) {
  Condition c;
  c.levels = std::move(levels);
  c.repetition = rep;
  c.seed = seed;
  c.id = "test";
  return c;
}

ExperimentSpec spec_for(const std::string& type, double width, double depth, double duration = 4.0) {
  ExperimentSpec s;
  s.seed = 5;
  s.scenario.type = parse_kind<ScenarioKind>(type).value();
  s.scenario.width_m = width;
  s.scenario.depth_m = depth;
  s.duration_s = duration;
  s.fps = 30.0;
  return s;
}

/// generate_scenario() of a hand-built condition, typed against `spec` as enumerate_conditions() types
/// the spec's own conditions.
ScenarioResult generate(const ExperimentSpec& spec, Condition c) {
  type_condition(spec, c);
  return generate_scenario(spec, c);
}

}  // namespace

TEST_CASE("scenarios: the stationary concert at seed 000's densities", "[crowd][scenario]") {
  const ExperimentSpec spec = spec_for("stationary", 3.0, 3.0, 2.0);
  const int expected[] = {20, 30, 40, 50, 60};
  const double densities[] = {2.22, 3.33, 4.44, 5.55, 6.66};
  for (int k = 0; k < 5; ++k) {
    const ScenarioResult r = generate(spec, condition({{"density", level(densities[k])}}));
    INFO("density " << densities[k]);
    CHECK(r.scenario == ScenarioKind::stationary);
    REQUIRE(r.trajectories.agents.size() == static_cast<std::size_t>(expected[k]));
    CHECK(r.trajectories.frame_count() == 60);
    CHECK(r.area_m2 == Approx(9.0));
    CHECK(r.achieved_density_per_m2 == Approx(densities[k]).epsilon(0.01));
    CHECK(r.min_spacing_m >= spec.crowd.agent_radius_m);
    REQUIRE(r.environment.boxes.size() == 1);  // the stage, in front (+Z)
    CHECK(r.environment.boxes[0].center_m.z() > 1.5);
    for (const AgentTrajectory& a : r.trajectories.agents) {
      const Vec2 p0 = a.position_m.front();
      for (std::size_t f = 0; f < a.position_m.size(); ++f) {
        CHECK((a.position_m[f] - p0).norm() < 0.1);  // in place: sway only
        CHECK(std::cos(a.heading_rad[f]) > 0.5);     // facing the stage at +Z
      }
      CHECK(std::fabs(p0.x()) <= 1.5 + 0.05);  // the base lies in the area; sway is <= 4 cm
      CHECK(std::fabs(p0.y()) <= 1.5 + 0.05);
    }
  }
  // The clip loops (issue 28): every sway and look-around runs whole cycles, so the step from the last
  // frame back to the first is an ordinary step.
  for (const AgentTrajectory& a : generate(spec, condition({{"density", level(2.22)}})).trajectories.agents) {
    const size_t n = a.position_m.size();
    double largest = 0.0;
    for (size_t f = 1; f < n; ++f)
      largest = std::max(largest, (a.position_m[f] - a.position_m[f - 1]).norm());
    CHECK((a.position_m.front() - a.position_m.back()).norm() <= 1.5 * largest + 1e-12);
    CHECK(std::fabs(a.heading_rad.front() - a.heading_rad.back()) <= 0.02);
  }
  // The characters factor wins over density.
  CHECK(generate(spec, condition({{"characters", level(25)}})).trajectories.agents.size() == 25);
}

TEST_CASE("scenarios: corridor densities hold within 5 %, walls are obstacles and boxes",
          "[crowd][scenario]") {
  const double w = 3.0, len = 8.0;
  for (double density : {2.2, 3.3, 4.4, 5.5, 6.6}) {
    const ExperimentSpec spec = spec_for("corridor", w, len, 4.0);
    const ScenarioResult r = generate(spec, condition({{"density", level(density)}}));
    INFO("density " << density);
    CHECK(r.scenario == ScenarioKind::corridor);
    CHECK(r.achieved_density_per_m2 == Approx(density).epsilon(0.05));
    REQUIRE(r.environment.boxes.size() == 2);
    const auto& agents = r.trajectories.agents;
    // Measured from positions: at frame 0 the crowd spans the corridor section (N / (w x extent));
    // over the clip the density is held: the 5-95 % quantile estimate at mid-clip and at the end is
    // within 5 % of the same estimate at frame 0.
    auto quantile_density = [&](std::size_t f) {
      std::vector<double> zs;
      for (const auto& a : agents) zs.push_back(a.position_m[f].y());
      std::sort(zs.begin(), zs.end());
      const double q05 = zs[static_cast<std::size_t>(0.05 * static_cast<double>(zs.size() - 1) + 0.5)];
      const double q95 = zs[static_cast<std::size_t>(0.95 * static_cast<double>(zs.size() - 1) + 0.5)];
      return 0.9 * static_cast<double>(zs.size()) / (w * (q95 - q05));
    };
    double zmin = 1e9, zmax = -1e9;
    for (const auto& a : agents)
      zmin = std::min(zmin, a.position_m[0].y()), zmax = std::max(zmax, a.position_m[0].y());
    CHECK(static_cast<double>(agents.size()) / (w * (zmax - zmin)) == Approx(density).epsilon(0.05));
    const double start = quantile_density(0);
    const double mid = quantile_density(static_cast<std::size_t>(r.trajectories.frame_count() / 2));
    const double end = quantile_density(static_cast<std::size_t>(r.trajectories.frame_count() - 1));
    INFO("start " << start << " mid " << mid << " end " << end);
    CHECK(mid == Approx(start).epsilon(0.05));
    CHECK(end == Approx(start).epsilon(0.05));
    for (const auto& a : agents) {
      CHECK(a.radius_m <= spec.crowd.agent_radius_m);
      for (const Vec2& p : a.position_m) CHECK(std::fabs(p.x()) < 0.5 * w);
      CHECK(a.position_m.back().y() > a.position_m.front().y() + 1.0);  // walking along +Z
    }
  }
}

TEST_CASE("scenarios: pair crossing hits the requested distance within 1 cm at mid-clip",
          "[crowd][scenario]") {
  ExperimentSpec spec = spec_for("pair_crossing", 4.0, 8.0, 4.0);
  for (int k = 0; k <= 10; ++k) {
    const double D = 0.2 + 0.05 * k;
    for (const char* side : {"left", "right"}) {
      const ScenarioResult r =
          generate(spec, condition({{"distance", level(D)}, {"side", FactorLevel{side, std::nullopt}}}));
      REQUIRE(r.trajectories.agents.size() == 2);
      const auto& a = r.trajectories.agents[0].position_m;
      const auto& b = r.trajectories.agents[1].position_m;
      std::size_t best = 0;
      for (std::size_t f = 0; f < a.size(); ++f)
        if ((a[f] - b[f]).norm() < (a[best] - b[best]).norm()) best = f;
      INFO("D " << D << " side " << side);
      CHECK((a[best] - b[best]).norm() == Approx(D).margin(0.01));
      CHECK(static_cast<double>(best) == Approx((a.size() - 1) / 2.0).margin(0.5));
      // Character 0 walks +Z; on a left pass the other is on its left (+X).
      const double lateral = b[best].x() - a[best].x();
      CHECK((std::string(side) == "left" ? lateral > 0 : lateral < 0));
    }
  }
  // alternate: odd repetitions left, even right.
  spec.scenario.passing_side = PassingSide::alternate;
  const auto r1 = generate(spec, condition({{"distance", level(0.4)}}, 1));
  const auto r2 = generate(spec, condition({{"distance", level(0.4)}}, 2));
  CHECK(r1.trajectories.agents[1].position_m[0].x() > 0);
  CHECK(r2.trajectories.agents[1].position_m[0].x() < 0);
  CHECK_THROWS_WITH(generate(spec, condition({})), Catch::Contains("distance"));
}

TEST_CASE("scenarios: flow densities match seed 001's levels within 5 %", "[crowd][scenario]") {
  for (const char* type : {"A", "B"}) {
    ExperimentSpec spec = spec_for("stationary", 6.0, 12.0, 3.0);  // the scenario factor overrides the type
    spec.crowd.model = CrowdModel::cost;
    for (double density : {0.5, 0.7, 1.0, 1.6, 2.8}) {
      const ScenarioResult r = generate(
          spec, condition({{"scenario", FactorLevel{type, std::nullopt}}, {"density", level(density)}}));
      INFO("scenario " << type << " density " << density);
      CHECK(r.scenario == (std::string(type) == "A" ? ScenarioKind::flow_a : ScenarioKind::flow_b));
      CHECK(r.achieved_density_per_m2 == Approx(density).epsilon(0.05));
      // Independent check at frame 0: crowd members per area of their lattice blocks.
      const double s = 1.0 / std::sqrt(density);
      int crowd = 0, focal = 0;
      Vec2 lo(1e9, 1e9), hi(-1e9, -1e9);
      for (const auto& a : r.trajectories.agents) {
        if (std::string(type) == "A" && a.group == 1) {
          ++focal;
          continue;
        }
        ++crowd;
        lo = lo.cwiseMin(a.position_m[0]);
        hi = hi.cwiseMax(a.position_m[0]);
      }
      if (std::string(type) == "A") {
        CHECK(focal == 1);
        const double cells =
            std::round((hi.x() - lo.x()) / s + 1.0) * std::round((hi.y() - lo.y()) / s + 1.0);
        CHECK(crowd / (cells * s * s) == Approx(density).epsilon(0.05));
      }
      CHECK(crowd >= 10);
    }
  }
}

TEST_CASE("scenarios: bad parameters are refused naming their key", "[crowd][scenario]") {
  ExperimentSpec spec = spec_for("stationary", 3.0, 3.0, 1.0);
  const Condition c = condition({{"density", level(4.44)}});
  spec.crowd.agent_radius_m = -0.2;
  CHECK_THROWS_WITH(generate(spec, c), Catch::Contains("crowd.agent_radius_m"));
  // The spec loader checks the ranges; a spec built in code that breaks one breaks a precondition.
  CHECK_THROWS_AS(generate(spec, c), std::logic_error);
  spec = spec_for("stationary", 0.0, 3.0, 1.0);
  CHECK_THROWS_WITH(generate(spec, c), Catch::Contains("scenario.width_m"));
  spec = spec_for("stationary", 3.0, 3.0, 1.0);
  CHECK_THROWS_WITH(generate(spec, condition({{"characters", level(400)}})),
                    Catch::Contains("cannot fit") || Catch::Contains("cannot be placed"));
  CHECK_THROWS_WITH(generate(spec, condition({{"density", level(-1)}})), Catch::Contains("factors.density"));
  CHECK_THROWS_WITH(generate(spec, condition({})), Catch::Contains("crowd size is unknown"));
  spec.scenario.type = ScenarioKind::manifold;
  CHECK_THROWS_WITH(generate(spec, c), Catch::Contains("surface stage"));
  spec = spec_for("flow_b", 0.3, 8.0, 1.0);
  CHECK_THROWS_AS(generate(spec, c), InputError);
  spec = spec_for("corridor", 3.0, 8.0, 1.0);
  spec.fps = 0;
  CHECK_THROWS_WITH(generate(spec, c), Catch::Contains("fps"));
}

TEST_CASE("scenarios: deterministic per seed and thread count", "[crowd][scenario][determinism]") {
  const ExperimentSpec spec = spec_for("corridor", 3.0, 8.0, 3.0);
  const Condition c = condition({{"density", level(5.5)}});
  auto hash = [&](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                              static_cast<std::size_t>(threads));
    return test::trajectories_hash(generate(spec, c).trajectories);
  };
  const std::string h1 = hash(1);
  CHECK(h1 == hash(2));
  CHECK(h1 == hash(1));
  CHECK(h1 !=
        test::trajectories_hash(generate(spec, condition({{"density", level(5.5)}}, 1, 78)).trajectories));
}

TEST_CASE("scenarios: Table 2 counts colliding pair-frames over all pairs, varying per repetition",
          "[crowd][scenario][measures]") {
  // The count of count_spec_collisions is sum over frames of the pairs whose discs overlap; checked
  // against a brute-force count over all pairs of the same trajectories, for both flows.
  ExperimentSpec spec = spec_for("flow_b", 6.0, 12.0, test::kSanitized ? 3.0 : 6.0);
  spec.crowd.model = CrowdModel::cost;
  spec.crowd.cost_weights = {{"separation", 1.0}, {"sigma_m", 0.3}, {"lookahead_s", 2.0}};
  for (const char* type : {"A", "B"}) {
    std::vector<Condition> conditions;
    for (int rep = 1; rep <= 3; ++rep) {
      conditions.push_back(condition({{"scenario", FactorLevel{type, std::nullopt}}, {"density", level(2.8)}},
                                     rep, 100 + rep));
      type_condition(spec, conditions.back());
    }
    const auto counts = count_spec_collisions(spec, conditions);
    REQUIRE(counts.size() == 3);
    for (std::size_t k = 0; k < counts.size(); ++k) {
      const auto t = generate(spec, conditions[k]).trajectories;
      long long brute = 0;
      for (int f = 0; f < t.frame_count(); ++f)
        for (std::size_t i = 0; i < t.agents.size(); ++i)
          for (std::size_t j = i + 1; j < t.agents.size(); ++j)
            if ((t.agents[i].position_m[static_cast<std::size_t>(f)] -
                 t.agents[j].position_m[static_cast<std::size_t>(f)])
                    .norm() < t.agents[i].radius_m + t.agents[j].radius_m)
              ++brute;
      INFO("scenario " << type << " repetition " << counts[k].repetition);
      CHECK(counts[k].scenario == type);
      CHECK(counts[k].collisions == brute);
      CHECK(counts[k].collisions > 0);
      CHECK(counts[k].events <= counts[k].collisions);  // every event lasts at least one frame
    }
    // Different random initialisations give different counts (seed 001 §4.2.1: 3 repetitions).
    CHECK((counts[0].collisions != counts[1].collisions || counts[1].collisions != counts[2].collisions));
  }
}

}  // namespace test_scenarios
