#include "framework/pipeline/crowd_key.hpp"

#include "framework/core/seed.hpp"
#include "framework/spec/type_condition.hpp"

namespace crowdlab {

std::string crowd_key(const Condition& condition) {
  std::string key;
  for (const auto& [name, level] : condition.levels) {
    if (is_presentation_factor(name)) continue;
    key += name + "-" + level.text + "_";
  }
  key += "rep-" + std::to_string(condition.repetition);
  return condition.practice ? "practice_" + key : key;
}

Condition crowd_condition(const ExperimentSpec& spec, const Condition& condition) {
  Condition c = condition;
  c.seed = derive_seed(spec.seed, "crowd/" + crowd_key(condition));
  return c;
}

}  // namespace crowdlab
