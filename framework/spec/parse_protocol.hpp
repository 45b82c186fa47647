#pragma once
// Reading `protocol:` (the study a participant runs) from YAML (internal to the spec loader).
// Keys, types and ranges are listed in docs/spec-reference.md. Scale sizes are limited to 2..11 points
// (the usual Likert/rating range; seed 000 uses 6 points, seed 001 uses 7).
#include "framework/spec/experiment_spec.hpp"
#include "framework/spec/yaml_section.hpp"

namespace crowdlab {

/// Fills spec.protocol from `section`. Checks that practice factors and block_by name factors that
/// `spec.factors` declares, so the factors must be parsed first.
void parse_protocol(YamlSection section, ExperimentSpec& spec);

}  // namespace crowdlab
