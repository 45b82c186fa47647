#include "framework/spec/condition_viewpoint.hpp"

#include "framework/core/viewpoint_catalogue.hpp"

namespace crowdlab {

std::string condition_viewpoint(const ExperimentSpec& spec, const Condition& condition) {
  const FactorLevel* level = condition.level("viewpoint");
  return level ? level->text : default_viewpoint(spec.scenario.type);
}

}  // namespace crowdlab
