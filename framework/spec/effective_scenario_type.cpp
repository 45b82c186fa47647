#include "framework/spec/effective_scenario_type.hpp"

namespace crowdlab {

std::string effective_scenario_type(const ExperimentSpec& spec, const Condition& condition) {
  const std::string level = condition.text("scenario", spec.scenario.type);
  if (level == "A") return "flow_a";
  if (level == "B") return "flow_b";
  return level;
}

}  // namespace crowdlab
