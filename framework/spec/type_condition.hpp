#pragma once
// type_condition: fills condition.params from condition.levels, condition.repetition and the spec's
// defaults, validating each level once. enumerate_conditions() calls it for every condition; a caller
// that builds a Condition by hand calls it too.
//   Inputs:  spec (scenario.type, scenario.passing_side), condition.levels, condition.repetition
//   Output:  condition.params
//   Throws:  InputError naming factors.<name> when a level is not a valid value of its factor (the
//            loader has already checked the spec's own levels, so only hand-built levels can fail).
#include "framework/spec/experiment_spec.hpp"

namespace crowdlab {

void type_condition(const ExperimentSpec& spec, Condition& condition);

/// True for factors that change how a crowd is shown (viewpoint, method), not the crowd itself: the
/// conditions that differ only in them share one crowd (framework/pipeline/crowd_key.hpp).
bool is_presentation_factor(const std::string& factor_name);

}  // namespace crowdlab
