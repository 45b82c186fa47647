#pragma once
// count_spec_collisions: the disc collision events (disc_collision_events.hpp) of one trajectory set per
// scenario x density x repetition of a spec's conditions, the input of seed 001 Table 2
// (collision_table.hpp). Other factors (trigger, viewpoint, method...) do not change the 2D crowd, so
// each (resolved scenario type, density level, repetition) is generated once, with the seed of the
// first condition that has it.
#include <vector>

#include "framework/crowd/collision_table.hpp"
#include "framework/spec/experiment_spec.hpp"

namespace crowdlab {

/// One CollisionCount per distinct (scenario, density, repetition), in condition order. The scenario
/// is the condition's `scenario` level (e.g. "A") or else the resolved type; density the `density`
/// level or else the achieved density. Shows a Progress bar per trajectory set.
/// Throws InputError like generate_scenario.
std::vector<CollisionCount> count_spec_collisions(const ExperimentSpec& spec,
                                                  const std::vector<Condition>& conditions);

}  // namespace crowdlab
