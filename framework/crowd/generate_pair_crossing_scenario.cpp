// Pair crossing (seed 001 §3.1, experiment 1): two characters walk past each other on parallel,
// opposite lines. The interpersonal distance is "computed as the distance between the root of the
// characters at the time of interaction, i.e., when the distance between characters is minimal", and
// clips are "aligned in time based on their respective time of interaction".
//   * character 0 walks +Z on x = -s D/2, character 1 walks -Z on x = +s D/2, both at walk_speed_mps,
//     with D the `distance` factor (m) and s = +1 when passing on the left, -1 on the right. A
//     character's left is +X when facing +Z (crowdlab convention), so with s = +1 each sees the other
//     on its left;
//   * side: the `side` factor (left | right) when present, else scenario.passing_side: left, right or
//     alternate (odd repetitions left, even right: seed 001 crossed on the left in half the repetitions);
//   * the closest approach (root distance exactly D) falls on frame round((frames - 1) / 2);
//   * no navigation model: the experiment controls the distance exactly (seed 001's actors followed
//     lines on the floor). Group 0 / 1 identify the two characters.
#include <cmath>
#include <numbers>

#include "framework/core/precondition.hpp"
#include "framework/crowd/generate_scenario.hpp"

namespace crowdlab {

ScenarioResult generate_pair_crossing_scenario(const ExperimentSpec& spec, const Condition& condition) {
  precondition(condition.params.distance_m.has_value(),
               "factors.distance: a pair_crossing scenario needs one");
  const double D = *condition.params.distance_m;
  const double s = condition.params.side == PassingSide::left ? 1.0 : -1.0;
  const double v = spec.scenario.walk_speed_mps;
  const int frames = std::max(1, static_cast<int>(std::lround(spec.duration_s * spec.fps)));
  const double t_mid = std::lround((frames - 1) / 2.0) / spec.fps;

  ScenarioResult r;
  r.trajectories.fps = spec.fps;
  r.trajectories.agents.resize(2);
  for (int c = 0; c < 2; ++c) {
    AgentTrajectory& a = r.trajectories.agents[static_cast<std::size_t>(c)];
    const double dir = c == 0 ? 1.0 : -1.0;  // +Z for character 0
    const double x = -dir * s * 0.5 * D;
    a.radius_m = spec.crowd.agent_radius_m;
    a.group = c;
    a.position_m.resize(static_cast<std::size_t>(frames));
    a.heading_rad.assign(static_cast<std::size_t>(frames), c == 0 ? 0.0 : std::numbers::pi);
    for (int f = 0; f < frames; ++f)
      a.position_m[static_cast<std::size_t>(f)] = Vec2(x, dir * v * (f / spec.fps - t_mid));
  }
  r.area_m2 = spec.scenario.width_m * spec.scenario.depth_m;
  r.achieved_density_per_m2 = 2.0 / r.area_m2;
  r.min_spacing_m = D;
  return r;
}

}  // namespace crowdlab
