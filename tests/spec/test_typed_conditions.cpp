// Typed conditions (issue 22.3): every condition's levels reach ConditionParams once, with the spec's
// defaults, and hand-built levels that are not values of their factor are refused by name.
#include <catch2/catch.hpp>

#include "framework/core/error.hpp"
#include "framework/core/viewpoint_catalogue.hpp"
#include "framework/spec/load_experiment_spec.hpp"
#include "framework/spec/type_condition.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_typed_conditions {

using namespace crowdlab;

namespace {

ExperimentSpec load_text(const std::string& text) {
  return load_experiment_spec_text("crowdlab: 1\nname: t\nseed: 5\n" + text, "t.yaml", ".");
}

}  // namespace

TEST_CASE("typed conditions carry every factor of the paper specs as typed values") {
  const ExperimentSpec spec = load_text(
      "scenario: {type: stationary}\n"
      "factors: {density: [2.22, 6.66], viewpoint: [V1, V4], method: [baseline, ours]}\n");
  const auto conditions = enumerate_conditions(spec);
  REQUIRE(conditions.size() == 8);
  for (const Condition& c : conditions) {
    CAPTURE(c.id);
    CHECK(c.params.scenario == ScenarioKind::stationary);
    REQUIRE(c.params.density_per_m2);
    CHECK(*c.params.density_per_m2 == c.levels.at("density").number.value());
    CHECK_FALSE(c.params.characters);
    CHECK(viewpoint_name(c.params.viewpoint) == c.levels.at("viewpoint").text);
    CHECK(kind_name(c.params.method) == c.levels.at("method").text);
  }
  CHECK(conditions.front().params.method == CrowdMethod::baseline);
  CHECK(conditions.back().params.method == CrowdMethod::corrected);
  CHECK(conditions.back().params.viewpoint == ViewpointId::V4);
}

TEST_CASE("typed conditions take the spec's defaults: viewpoint by scenario, passing side by repetition") {
  const ExperimentSpec pair = load_text(
      "scenario: {type: pair_crossing, passing_side: alternate}\n"
      "factors: {distance: [0.4, 1.2], shoulder: [0, 2]}\nrepetitions: 2\n");
  const auto conditions = enumerate_conditions(pair);
  REQUIRE(conditions.size() == 8);
  for (const Condition& c : conditions) {
    CAPTURE(c.id);
    CHECK(c.params.viewpoint == ViewpointId::pair);   // seed 001 §3.1.4's three-quarter view
    CHECK(c.params.method == CrowdMethod::baseline);  // no method factor
    REQUIRE(c.params.distance_m);
    REQUIRE(c.params.shoulder_count);
    CHECK(*c.params.shoulder_count == static_cast<int>(c.levels.at("shoulder").number.value()));
    CHECK(c.params.side == (c.repetition == 1 ? PassingSide::left : PassingSide::right));
  }
  const ExperimentSpec flows =
      load_text("scenario: {type: corridor}\nfactors: {scenario: [A, B], trigger: [25%]}\n");
  const auto flow_conditions = enumerate_conditions(flows);
  REQUIRE(flow_conditions.size() == 2);
  CHECK(flow_conditions[0].params.scenario == ScenarioKind::flow_a);
  CHECK(flow_conditions[0].params.viewpoint == ViewpointId::tracking);
  CHECK(flow_conditions[1].params.scenario == ScenarioKind::flow_b);
  CHECK(flow_conditions[1].params.viewpoint == ViewpointId::V1);
  CHECK(flow_conditions[1].params.trigger_probability == Approx(0.25));
  const ExperimentSpec fixed = load_text(
      "scenario: {type: pair_crossing, passing_side: right}\n"
      "factors: {distance: [0.4], side: [left]}\nrepetitions: 2\n");
  for (const Condition& c : enumerate_conditions(fixed)) CHECK(c.params.side == PassingSide::left);
}

TEST_CASE("type_condition refuses hand-built levels that are not values of their factor") {
  const ExperimentSpec spec = load_text("scenario: {type: stationary}\n");
  Condition c;
  c.levels["density"] = FactorLevel{"-1", -1.0};
  CHECK_THROWS_WITH(type_condition(spec, c), Catch::Contains("factors.density"));
  // parse_factor checked the ranges (file:line:column): here they are preconditions, a programming error
  // when broken, not an input error (issue 30).
  CHECK_THROWS_AS(type_condition(spec, c), std::logic_error);
  c.levels = {{"characters", FactorLevel{"2.5", 2.5}}};
  CHECK_THROWS_WITH(type_condition(spec, c), Catch::Contains("factors.characters"));
  c.levels = {{"method", FactorLevel{"theirs", std::nullopt}}};
  CHECK_THROWS_WITH(type_condition(spec, c), Catch::Contains("factors.method"));
  c.levels = {{"viewpoint", FactorLevel{"V9", std::nullopt}}};
  CHECK_THROWS_WITH(type_condition(spec, c), Catch::Contains("factors.viewpoint"));
  CHECK_THROWS_AS(type_condition(spec, c), std::logic_error);
  c.levels = {{"characters", FactorLevel{"12", 12.0}}, {"method", FactorLevel{"ours", std::nullopt}}};
  type_condition(spec, c);
  CHECK(c.params.characters == 12);
  CHECK(c.params.method == CrowdMethod::corrected);
  CHECK(c.params.viewpoint == ViewpointId::V1);
}

TEST_CASE("the enums' spellings round-trip, and the loader refuses the others with the key") {
  for (const std::string& name : kind_names<ScenarioKind>())
    CHECK(kind_name(parse_kind<ScenarioKind>(name).value()) == name);
  CHECK_FALSE(parse_kind<BodyModel>("smpl"));
  CHECK(kind_name(CrowdMethod::corrected) == "ours");
  try {
    load_text("animation: {motion: mocap}\n");
    FAIL("a motion that is not procedural or clips loaded");
  } catch (const SpecError& e) {
    CHECK_THAT(e.what(), Catch::Contains("animation.motion") && Catch::Contains("mocap"));
  }
}

}  // namespace test_typed_conditions
