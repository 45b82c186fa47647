#pragma once
// ConditionParams: the typed settings of one condition, parsed and validated once from its factor
// levels and the spec's defaults by type_condition() (framework/spec/type_condition.hpp). Stages read
// these fields; the level texts in Condition::levels stay for ids, file names and response tables.
#include <optional>
#include <string>

#include "framework/core/viewpoint_catalogue.hpp"
#include "framework/spec/condition_kinds.hpp"

namespace crowdlab {

struct ConditionParams {
  /// The `scenario` factor's level (seed 001 §4.2.1's A -> flow_a, B -> flow_b), else scenario.type.
  ScenarioKind scenario = ScenarioKind::stationary;
  std::optional<double> density_per_m2;  ///< `density` factor, characters per m^2 (> 0)
  std::optional<int> characters;         ///< `characters` factor (>= 1)
  /// A catalogue id (framework/core/viewpoint_catalogue.hpp): the `viewpoint` factor's level, else the
  /// scenario's default viewpoint.
  ViewpointId viewpoint = ViewpointId::V1;
  CrowdMethod method = CrowdMethod::baseline;  ///< `method` factor; baseline without one
  std::optional<int> shoulder_count;           ///< `shoulder` factor: characters with shoulder motions
  std::optional<double> distance_m;            ///< `distance` factor (pair_crossing), metres (> 0)
  double trigger_probability = 0.0;            ///< `trigger` factor (percent) / 100
  /// `side` factor, else scenario.passing_side; `alternate` resolved by repetition (odd: left).
  PassingSide side = PassingSide::left;
};

}  // namespace crowdlab
