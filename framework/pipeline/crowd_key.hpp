#pragma once
// Which conditions show the same crowd. The crowd key is the condition id without the presentation
// factors `viewpoint` and `method`: every viewpoint and both methods of one design cell show the same
// crowd (seed 000 §4.4.1: "for each viewpoint-density-scenario combination, we generate an animation
// with and without solving collisions"). Practice conditions get the prefix "practice_".
#include <string>

#include "framework/spec/experiment_spec.hpp"

namespace crowdlab {

/// "density-2.22_rep-1" for condition "density-2.22_viewpoint-V1_method-ours_rep-1".
std::string crowd_key(const Condition& condition);

/// `condition` with the seed of its crowd group: derive_seed(spec.seed, "crowd/" + crowd_key(condition)).
Condition crowd_condition(const ExperimentSpec& spec, const Condition& condition);

}  // namespace crowdlab
