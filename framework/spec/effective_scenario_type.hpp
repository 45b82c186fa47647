#pragma once
// The scenario a condition runs: its `scenario` factor level when the spec has one, else scenario.type.
#include <string>

#include "framework/spec/experiment_spec.hpp"

namespace crowdlab {

/// "stationary" | "corridor" | "pair_crossing" | "flow_a" | "flow_b" | "manifold". The level names of
/// seed 001 §4.2.1 map to flows: A (one character against a unidirectional flow) -> "flow_a",
/// B (bidirectional flow) -> "flow_b".
std::string effective_scenario_type(const ExperimentSpec& spec, const Condition& condition);

}  // namespace crowdlab
