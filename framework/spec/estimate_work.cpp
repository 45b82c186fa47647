#include "framework/spec/estimate_work.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "framework/spec/condition_kinds.hpp"
#include "framework/spec/work_limits.hpp"
#include "framework/spec/yaml_section.hpp"

namespace crowdlab {
namespace {

double condition_count(const ExperimentSpec& spec) {
  double conditions = spec.repetitions;
  for (const Factor& f : spec.factors) conditions *= static_cast<double>(f.levels.size());
  return conditions;
}

/// How many conditions enumerate_practice_conditions makes, from the level counts (nothing enumerated):
/// the practice factors crossed with the block factor when practice does not name it.
double practice_condition_count(const ExperimentSpec& spec) {
  const ProtocolSpec& p = spec.protocol;
  if (p.practice_factors.empty()) return 0.0;
  double count = 1.0;
  bool blocks_named = false;
  for (const Factor& f : p.practice_factors) {
    count *= static_cast<double>(f.levels.size());
    blocks_named = blocks_named || f.name == p.block_by;
  }
  if (!p.block_by.empty() && !blocks_named)
    if (const Factor* block = spec.factor(p.block_by)) count *= static_cast<double>(block->levels.size());
  return count;
}

// Flows place a lattice of spacing s = 1/sqrt(density) (else initial_spacing_m) over the area, one per
// group (generate_flow_scenario.cpp); counted here in double, so that a flow-B of density 10 on 1000 m
// (20 million agents: 5 GB at 180 s) is refused before it is placed (issue 33).
double largest_flow(const ExperimentSpec& spec) {
  const ScenarioSpec& sc = spec.scenario;
  const double groups = sc.type == ScenarioKind::flow_b ? 2.0 : 1.0;
  std::vector<double> spacings;
  if (const Factor* density = spec.factor("density"))
    for (const FactorLevel& l : density->levels)
      if (l.number.value_or(0.0) > 0.0) spacings.push_back(1.0 / std::sqrt(*l.number));
  if (spacings.empty()) spacings.push_back(sc.initial_spacing_m);
  double most = 0.0;
  for (const double s : spacings) {
    if (!(s > 0.0)) continue;
    const double cols = std::floor(sc.width_m / s + 1e-9);
    const double rows = sc.agents > 0 ? std::ceil(sc.agents / groups / std::max(cols, 1.0))
                                      : std::floor(sc.depth_m / (groups * s) + 1e-9);
    most = std::max(most, groups * rows * cols + (groups == 1.0 ? 1.0 : 0.0));
  }
  return most;
}

}  // namespace

double crowd_on_area(double density_per_m2, double area_m2) {
  return std::round(density_per_m2 * area_m2);
}

double largest_crowd_on_area(const ExperimentSpec& spec, double area_m2) {
  double most = spec.scenario.agents;
  if (const Factor* characters = spec.factor("characters")) {
    for (const FactorLevel& l : characters->levels) most = std::max(most, l.number.value_or(0.0));
    return most;
  }
  if (const Factor* density = spec.factor("density"))
    for (const FactorLevel& l : density->levels)
      most = std::max(most, crowd_on_area(l.number.value_or(0.0), area_m2));
  return most;
}

SpecWork estimate_spec_work(const ExperimentSpec& spec) {
  SpecWork w;
  w.conditions = condition_count(spec);
  w.practice_conditions = practice_condition_count(spec);
  w.frames = std::ceil(spec.duration_s * spec.fps);
  const ScenarioKind kind = spec.scenario.type;
  w.largest_crowd = spec.scenario.agents;
  if (kind == ScenarioKind::flow_a || kind == ScenarioKind::flow_b)
    w.largest_crowd = std::max(w.largest_crowd, largest_flow(spec));
  // The characters factor sizes every kind; density sizes area scenarios (flows read it as spacing).
  if (spec.factor("characters") || is_area_scenario(kind))
    w.largest_crowd =
        std::max(w.largest_crowd,
                 largest_crowd_on_area(
                     spec, is_area_scenario(kind) ? spec.scenario.width_m * spec.scenario.depth_m : 0.0));
  return w;
}

std::optional<std::string> crowd_limit_problem(const std::string& crowd, double characters, double frames,
                                               const std::string& fix_characters,
                                               const std::string& fix_frames) {
  if (characters > kMaxCharactersPerCrowd)
    return crowd + " has " + format_number(characters) + " characters, more than the limit of " +
           format_number(kMaxCharactersPerCrowd) + " characters in one crowd; " + fix_characters;
  if (characters * frames > kMaxCharacterFrames)
    return crowd + " has " + format_number(characters) + " characters x " + format_number(frames) +
           " frames = " + format_number(characters * frames) + " character-frames, more than the limit of " +
           format_number(kMaxCharacterFrames) + "; " + fix_frames;
  return std::nullopt;
}

std::optional<std::string> report_limit_problem(double participants, double items, double limit,
                                                const std::string& option) {
  const double work = participants * items;
  if (work <= limit) return std::nullopt;
  return format_number(participants) + " participants x " + format_number(items) +
         " Likert items (one mixed model each, a random intercept per participant) = " + format_number(work) +
         " participant-items, more than the limit of " + format_number(limit) +
         " (about 0.01 s each); raise it with " + option + " or analyse a subset of the participants";
}

}  // namespace crowdlab
