#pragma once
// Reading one design factor from YAML (internal to the spec loader). Used for `factors:` and for
// `protocol.practice:`.
//
// A factor is written either as a plain list or as a map with `levels:`:
//   density: [2.22, 3.33]            or      density: {levels: [2.22, 3.33]}
// Known factors and their valid levels (docs/spec-reference.md):
//   density    characters per m^2, number in (0, 10]  (seed 000 §4.4.1 uses 2.22..6.66; beyond ~6-7/m^2
//              crowds are at crush risk, Still 2000, so 10 is a generous ceiling)
//   characters character count, whole number in [1, 10000]
//   viewpoint  V1 front, V2 upper-front, V3 front-side, V4 overhead (seed 000 §4.4.1), pair (seed 001
//              §3.1.4 canonical pair view), tracking (follows the focal character)
//   method     baseline | ours (seed 000 §4.4.1)
//   shoulder   0 | 1 | 2 characters showing shoulder motions (seed 001 §3.1.3)
//   distance   interpersonal distance at closest approach, metres, in (0, 10] (seed 001: 0.2..0.7)
//   trigger    shoulder-reaction probability in percent, [0, 100]; "33%" is read as 33 (seed 001 §4.2.1)
//   scenario   a scenario type (stationary, corridor, pair_crossing, flow_a, flow_b, manifold) or A / B
//              (seed 001 §4.2.1: A = flow_a, B = flow_b)
//   side       left | right passing side
// The level text (as written, "%" stripped) is what condition ids use, so it may contain only
// letters, digits, '.', '+' and '-'. Duplicate levels (same text, or equal numbers) are errors, one per
// repeated level (issue 32: a factor listing V4 5,000 times made one error per earlier copy, 12.5
// million messages and 6.5 GB). A list longer than kMaxFactorLevels is refused from its length, before
// any level is read.
#include <optional>
#include <string>
#include <vector>

#include "framework/spec/experiment_spec.hpp"
#include "framework/spec/yaml_section.hpp"

namespace crowdlab {

/// Most levels one factor may list (the condition limit of load_experiment_spec.cpp: more levels could
/// never fit in a spec).
inline constexpr std::size_t kMaxFactorLevels = 10000;

/// The factor names a spec may use, in documentation order.
const std::vector<std::string>& known_factor_names();

/// Parses `node` (a list or {levels: [...]}) as factor `name`; path is e.g. "factors.density".
/// Returns nullopt (after recording errors) when any level is invalid or the list is empty.
std::optional<Factor> parse_factor(SpecDiagnostics& diag, const std::string& name, const YAML::Node& node,
                                   const std::string& path);

}  // namespace crowdlab
