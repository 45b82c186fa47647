#pragma once
// generate_scenario: one condition's 2D crowd (where each character stands and how it moves) for the
// papers' scenarios, from the spec's scenario.* and crowd.* sections and the condition's factors.
//
// Scenario kind: condition.params.scenario (its `scenario` factor, else scenario.type). Crowd size: the
// `characters` factor, else round(density * area) from the `density` factor (characters per m^2), else
// scenario.agents; the levels are read from condition.params, typed and validated once by the spec layer.
// Randomness: derive_seed(condition.seed, "<stage key>") per stream. Positions are world (x, z) metres;
// the ground is y = 0.
//   stationary    (seed 000 §4.1) concert on width x depth: Poisson-disk positions, in-place sway and
//                 heading toward a stage placed in front of the area.
//   corridor      (seed 000 §4.1/§4.4) walking along +Z in a corridor of width x length, walls as
//                 obstacles and as boxes in the Environment.
//   pair_crossing (seed 001 §3.1) two characters on parallel opposite lines; closest root distance
//                 = the `distance` factor; passing side from `side` or scenario.passing_side;
//                 closest approach at the middle frame.
//   flow_a/flow_b (seed 001 §4.2.1) one character against a unidirectional flow / two groups in a
//                 bidirectional flow, initial square-lattice spacing s = 1/sqrt(density) (0.6 .. 1.4 m
//                 give 2.8 .. 0.5 per m^2, matching seed 001's levels), or scenario.initial_spacing_m.
// Each generator's header documents its choices.
#include <string>

#include "framework/core/crowd_animation.hpp"
#include "framework/core/trajectories.hpp"
#include "framework/spec/experiment_spec.hpp"

namespace crowdlab {

struct ScenarioResult {
  CrowdTrajectories trajectories;  ///< sampled at spec.fps for spec.duration_s
  Environment environment;         ///< ground plane plus walls / stage boxes
  double area_m2 = 0.0;            ///< the area the density refers to
  double achieved_density_per_m2 = 0.0;
  double min_spacing_m = 0.0;  ///< smallest initial centre distance (pair_crossing: D at closest approach)
  ScenarioKind scenario = ScenarioKind::stationary;
};

/// Throws InputError for missing factors, bad parameters or impossible requests.
ScenarioResult generate_scenario(const ExperimentSpec& spec, const Condition& condition);

// The generators behind generate_scenario (inputs already validated by it).
ScenarioResult generate_stationary_scenario(const ExperimentSpec& spec, const Condition& condition);
ScenarioResult generate_corridor_scenario(const ExperimentSpec& spec, const Condition& condition);
ScenarioResult generate_pair_crossing_scenario(const ExperimentSpec& spec, const Condition& condition);
ScenarioResult generate_flow_scenario(const ExperimentSpec& spec, const Condition& condition, bool flow_b);

/// Characters for an area: `characters` factor, else round(density * area), else scenario.agents.
int scenario_character_count(const ExperimentSpec& spec, const Condition& condition, double area_m2);

}  // namespace crowdlab
