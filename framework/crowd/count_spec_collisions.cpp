#include "framework/crowd/count_spec_collisions.hpp"

#include <set>
#include <string>
#include <tuple>

#include "framework/core/progress.hpp"
#include "framework/crowd/disc_collision_events.hpp"
#include "framework/crowd/generate_scenario.hpp"

namespace crowdlab {

std::vector<CollisionCount> count_spec_collisions(const ExperimentSpec& spec,
                                                  const std::vector<Condition>& conditions) {
  // Viewpoint and method do not change the crowd: one count per scenario x density x repetition.
  std::set<std::tuple<ScenarioKind, double, int>> seen;
  std::vector<const Condition*> todo;
  for (const Condition& c : conditions)
    if (seen.insert({c.params.scenario, c.params.density_per_m2.value_or(0.0), c.repetition}).second)
      todo.push_back(&c);
  std::vector<CollisionCount> counts;
  Progress progress("crowd collision counts", todo.size());
  for (const Condition* cp : todo) {
    const Condition& c = *cp;
    const ScenarioResult r = generate_scenario(spec, c);
    const std::vector<CollisionEvent> events = disc_collision_events(r.trajectories);
    long long pair_frames = 0;
    for (const CollisionEvent& e : events) pair_frames += e.end_frame - e.start_frame;
    // Rows are labelled as the spec names the scenario (seed 001 Table 2 says A and B).
    counts.push_back({c.text("scenario", std::string(kind_name(r.scenario))),
                      c.params.density_per_m2.value_or(r.achieved_density_per_m2), c.repetition, pair_frames,
                      static_cast<long long>(events.size())});
    progress.advance();
  }
  progress.finish();
  return counts;
}

}  // namespace crowdlab
