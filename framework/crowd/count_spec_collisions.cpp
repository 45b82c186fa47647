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
  std::set<std::tuple<std::string, std::string, int>> seen;
  std::vector<const Condition*> todo;
  for (const Condition& c : conditions)
    if (seen.insert({resolve_scenario_type(spec, c), c.text("density", ""), c.repetition}).second)
      todo.push_back(&c);
  std::vector<CollisionCount> counts;
  Progress progress("crowd collision counts", todo.size());
  for (const Condition* cp : todo) {
    const Condition& c = *cp;
    const ScenarioResult r = generate_scenario(spec, c);
    const std::vector<CollisionEvent> events = disc_collision_events(r.trajectories);
    long long pair_frames = 0;
    for (const CollisionEvent& e : events) pair_frames += e.end_frame - e.start_frame;
    counts.push_back({c.text("scenario", r.scenario), c.number("density", r.achieved_density_per_m2),
                      c.repetition, pair_frames, static_cast<long long>(events.size())});
    progress.advance();
  }
  progress.finish();
  return counts;
}

}  // namespace crowdlab
