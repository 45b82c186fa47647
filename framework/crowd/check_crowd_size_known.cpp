#include "framework/crowd/check_crowd_size_known.hpp"

#include "framework/core/error.hpp"
#include "framework/spec/locate_spec_key.hpp"

namespace crowdlab {

bool crowd_size_known(const ExperimentSpec& spec, const Condition& condition) {
  switch (condition.params.scenario) {
    case ScenarioKind::stationary:
    case ScenarioKind::corridor:
    case ScenarioKind::manifold:
      return condition.params.characters || condition.params.density_per_m2 || spec.scenario.agents >= 1;
    case ScenarioKind::pair_crossing:
    case ScenarioKind::flow_a:
    case ScenarioKind::flow_b:
      return true;
  }
  return true;
}

void check_crowd_size_known(const ExperimentSpec& spec, const std::vector<Condition>& conditions) {
  for (const Condition& c : conditions) {
    if (crowd_size_known(spec, c)) continue;
    throw InputError(locate_spec_key(spec.source_path, "scenario.agents"),
                     "condition " + c.id +
                         ": no `characters` or `density` factor and scenario.agents is 0: the crowd size is "
                         "unknown (give one of them)");
  }
}

}  // namespace crowdlab
