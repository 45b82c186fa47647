#pragma once
// Whether every crowd a spec's conditions generate has a known size, checked before any work so that
// `validate` refuses what `run` would (issue 30: "validate catches everything run would refuse for the
// spec's own content"). The count itself is scenario_character_count (generate_scenario.hpp).
//
// Inputs: the typed spec and its conditions (main and practice). Output: nothing, or an InputError at
// scenario.agents' file:line:column (the key that gives a size when no factor does).
#include <vector>

#include "framework/spec/experiment_spec.hpp"

namespace crowdlab {

/// True when the condition's crowd is sized by a `characters` or `density` level or by scenario.agents,
/// or when its scenario kind sizes itself (pair crossings: two people; flows: their lattice).
bool crowd_size_known(const ExperimentSpec& spec, const Condition& condition);

/// Throws InputError naming scenario.agents for the first condition whose crowd size is unknown.
void check_crowd_size_known(const ExperimentSpec& spec, const std::vector<Condition>& conditions);

}  // namespace crowdlab
