#pragma once
// The one estimator of a study's work (issue 33 item 3): how many conditions a spec makes, how many
// characters its largest crowd has (density x area, a flow's lattice, the characters factor, scenario
// agents, density x a manifold's mesh area), how many frames a clip has, and how many participant-item
// models a report fits. Every limit check of a spec or a command asks this module, before any work,
// and refuses above the limit with the estimate, the limit and the key or option that raises it.
// The limits themselves are in framework/spec/work_limits.hpp.
//
// Inputs: the typed spec (units: metres, m^2, characters per m^2, seconds, frames per second).
// Outputs: counts as double, so that no estimate wraps around in an int before it is compared.
#include <optional>
#include <string>

#include "framework/spec/experiment_spec.hpp"

namespace crowdlab {

/// What a spec asks for, counted from its levels without enumerating anything.
struct SpecWork {
  double conditions = 0;           ///< factor levels x repetitions
  double practice_conditions = 0;  ///< practice levels, crossed with the blocks when practice omits them
  double largest_crowd = 0;        ///< characters of the largest 2D crowd (0: the spec gives no size)
  double frames = 0;               ///< frames of one clip: ceil(duration_s x fps)
};

/// The work of a spec's 2D scenarios (manifold crowds: largest_crowd_on_area with the mesh's area).
SpecWork estimate_spec_work(const ExperimentSpec& spec);

/// Largest crowd of any condition on `area_m2` (the characters factor, else density x area, else
/// scenario.agents), the count of scenario_character_count for every level at once.
double largest_crowd_on_area(const ExperimentSpec& spec, double area_m2);

/// Characters one density level places on `area_m2`, rounded as the generators round it.
double crowd_on_area(double density_per_m2, double area_m2);

/// The crowd limits: nullopt within kMaxCharactersPerCrowd and kMaxCharacterFrames, else a sentence
/// that gives the estimate and the limit. `crowd` names the crowd ("the largest crowd", "density 3 on
/// 20 m^2"); `fix_characters` and `fix_frames` say which keys or options to change for each limit.
std::optional<std::string> crowd_limit_problem(const std::string& crowd, double characters, double frames,
                                               const std::string& fix_characters,
                                               const std::string& fix_frames);

/// The report limit: participants x items fitted (one cumulative link mixed model per Likert item, each
/// with a random intercept per participant). nullopt within `limit`, else the estimate, the limit and
/// `option`, which raises it.
std::optional<std::string> report_limit_problem(double participants, double items, double limit,
                                                const std::string& option);

}  // namespace crowdlab
