#include "framework/spec/type_condition.hpp"

#include <cmath>

#include "framework/core/error.hpp"
#include "framework/core/precondition.hpp"
#include "framework/core/viewpoint_catalogue.hpp"

namespace crowdlab {
namespace {

// The one place that reads factor levels by name: every stage reads the typed fields instead.
std::optional<double> positive_number(const Condition& c, const std::string& factor,
                                      const std::string& units) {
  const FactorLevel* l = c.level(factor);
  if (!l) return std::nullopt;
  // parse_factor checked the level's range with file:line:column.
  precondition(l->number && *l->number > 0.0 && std::isfinite(*l->number),
               "factors." + factor + ": level '" + l->text + "' a positive number of " + units);
  return *l->number;
}

std::optional<int> whole_number(const Condition& c, const std::string& factor, double least) {
  const FactorLevel* l = c.level(factor);
  if (!l) return std::nullopt;
  precondition(l->number && *l->number >= least && std::floor(*l->number) == *l->number && *l->number <= 1e9,
               "factors." + factor + ": level '" + l->text +
                   "' a whole number >= " + std::to_string(static_cast<int>(least)));
  return static_cast<int>(*l->number);
}

template <class E>
E choice(const Condition& c, const std::string& factor, E fallback) {
  const FactorLevel* l = c.level(factor);
  if (!l) return fallback;
  if (auto v = parse_kind<E>(l->text)) return *v;
  throw InputError("factors." + factor + ": invalid level '" + l->text + "'");
}

// seed 001 §4.2.1 names its two flow scenarios A (one character against a unidirectional flow) and B
// (bidirectional flow); the spec accepts those names as `scenario` levels.
ScenarioKind scenario_of(const ExperimentSpec& spec, const Condition& c) {
  const FactorLevel* l = c.level("scenario");
  if (l && l->text == "A") return ScenarioKind::flow_a;
  if (l && l->text == "B") return ScenarioKind::flow_b;
  return choice(c, "scenario", spec.scenario.type);
}

// Without a `viewpoint` factor: "pair" for pair crossings (seed 001 §3.1.4's three-quarter view),
// "tracking" for flow A (seed 001 follows its focal character), V1 otherwise.
ViewpointId default_viewpoint(ScenarioKind scenario) {
  switch (scenario) {
    case ScenarioKind::pair_crossing:
      return ViewpointId::pair;
    case ScenarioKind::flow_a:
      return ViewpointId::tracking;
    default:
      return ViewpointId::V1;
  }
}

// The level's name becomes the catalogue id here, once; later stages carry the id.
ViewpointId viewpoint_of(const Condition& c, ScenarioKind scenario) {
  const FactorLevel* l = c.level("viewpoint");
  if (!l) return default_viewpoint(scenario);
  const std::optional<ViewpointId> id = find_viewpoint(l->text);
  precondition(id.has_value(), "factors.viewpoint: level '" + l->text + "' a catalogue viewpoint");
  return *id;
}

PassingSide side_of(const ExperimentSpec& spec, const Condition& c) {
  const PassingSide side = choice(c, "side", spec.scenario.passing_side);
  if (side != PassingSide::alternate) return side;
  return c.repetition % 2 == 1 ? PassingSide::left : PassingSide::right;
}

}  // namespace

void type_condition(const ExperimentSpec& spec, Condition& condition) {
  ConditionParams& p = condition.params;
  p.scenario = scenario_of(spec, condition);
  p.density_per_m2 = positive_number(condition, "density", "characters per m^2");
  p.characters = whole_number(condition, "characters", 1.0);
  p.viewpoint = viewpoint_of(condition, p.scenario);
  p.method = choice(condition, "method", CrowdMethod::baseline);
  p.shoulder_count = whole_number(condition, "shoulder", 0.0);
  p.distance_m = positive_number(condition, "distance", "metres");
  p.trigger_probability = condition.number("trigger", 0.0) / 100.0;
  p.side = side_of(spec, condition);
}

bool is_presentation_factor(const std::string& factor_name) {
  return factor_name == "viewpoint" || factor_name == "method";
}

}  // namespace crowdlab
