// Flow scenarios of seed 001 §4.2.1 (experiment 2):
//   A: "a single character walking against a unidirectional crowd flow";
//   B: "two large groups of characters walking in a bidirectional flow".
// Density is controlled by the initial distance between agents: seed 001 used 0.6 .. 1.4 m (0.2 m
// steps) for densities 2.8, 1.6, 1.0, 0.7, 0.5 per m^2, which is a square lattice: density = 1/s^2.
// So s = 1/sqrt(density) from the `density` factor (or scenario.initial_spacing_m without one).
// Choices where the paper is silent:
//   * a group is a lattice of cols = floor(width/s) columns (x) and rows rows (z) of s x s cells,
//     rows = floor(depth/s) for A and floor(depth/(2 s)) per group for B, or enough rows for
//     scenario.agents characters; each agent sits in its cell centre plus a uniform jitter of
//     +-10 % of s ("different random initialisations" per repetition). The density reported is
//     N / (cells x s^2) = 1/s^2;
//   * A: the flow (group 0) walks +Z; the focal character (group 1) starts s + 2.6 m in front of the
//     flow, at a lateral x uniform in [-s/2, s/2) drawn per repetition, and walks -Z through it (they
//     meet after about a second);
//   * B: group 0 starts behind z = -1 m walking +Z, group 1 ahead of z = +1 m walking -Z;
//   * preferred speeds walk_speed_mps x (1 + 0.05 N(0,1)) clamped to +-10 %; no walls.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "framework/core/error.hpp"
#include "framework/core/precondition.hpp"
#include "framework/core/seed.hpp"
#include "framework/crowd/generate_scenario.hpp"
#include "framework/crowd/make_navigation_model.hpp"
#include "framework/crowd/place_poisson_disk.hpp"
#include "framework/crowd/simulate_trajectories.hpp"

namespace crowdlab {
namespace {

double flow_spacing(const ExperimentSpec& spec, const Condition& condition) {
  if (condition.params.density_per_m2) return 1.0 / std::sqrt(*condition.params.density_per_m2);
  const double s = spec.scenario.initial_spacing_m;
  precondition(s > 0.0 && std::isfinite(s), "scenario.initial_spacing_m > 0 m");
  return s;
}

}  // namespace

ScenarioResult generate_flow_scenario(const ExperimentSpec& spec, const Condition& condition, bool flow_b) {
  const ScenarioSpec& sc = spec.scenario;
  const double s = flow_spacing(spec, condition);
  const int cols = static_cast<int>(std::floor(sc.width_m / s + 1e-9));
  if (cols < 1)
    throw InputError("scenario.width_m: " + std::to_string(sc.width_m) +
                     " m is narrower than the initial spacing " + std::to_string(s) + " m");
  const int groups = flow_b ? 2 : 1;
  int rows = static_cast<int>(std::floor(sc.depth_m / (groups * s) + 1e-9));
  if (sc.agents > 0) rows = (sc.agents / groups + cols - 1) / cols;
  if (rows < 1)
    throw InputError("scenario.depth_m: " + std::to_string(sc.depth_m) + " m holds no row at spacing " +
                     std::to_string(s) + " m");
  const double v0 = sc.walk_speed_mps;
  const double block = rows * s, x0 = -0.5 * cols * s;
  std::vector<AgentInit> agents;
  std::vector<int> group;
  std::vector<double> heading;
  auto add = [&](const Vec2& p, double dir, int g, const std::string& key) {
    Rng rng(derive_seed(condition.seed, key));
    AgentInit a;
    a.position = p;
    a.goal = Vec2(p.x(), dir * 1e4);
    a.radius_m = spec.crowd.agent_radius_m;
    a.preferred_speed_mps = v0 * std::clamp(1.0 + 0.05 * standard_normal(rng), 0.9, 1.1);
    a.max_speed_mps = std::max(spec.crowd.max_speed_mps, a.preferred_speed_mps);
    a.velocity = Vec2(0.0, dir * a.preferred_speed_mps);  // already walking at t = 0
    agents.push_back(a);
    group.push_back(g);
    heading.push_back(dir > 0 ? 0.0 : std::numbers::pi);
  };
  for (int g = 0; g < groups; ++g) {
    const double dir = g == 0 ? 1.0 : -1.0;
    // A: the flow block ends at z = 0; B: blocks end 1 m either side of z = 0.
    const double z_front = flow_b ? -dir * 1.0 : 0.0;
    for (int rrow = 0; rrow < rows; ++rrow) {
      for (int c = 0; c < cols; ++c) {
        const std::string key =
            "lattice/" + std::to_string(g) + "/" + std::to_string(rrow) + "/" + std::to_string(c);
        Rng rng(derive_seed(condition.seed, key));
        const double jx = (uniform01(rng) - 0.5) * 0.2 * s, jz = (uniform01(rng) - 0.5) * 0.2 * s;
        const Vec2 p(x0 + (c + 0.5) * s + jx, z_front - dir * (rrow + 0.5) * s + jz);
        add(p, dir, g, "speed/" + key);
      }
    }
  }
  const std::size_t crowd_size = agents.size();
  if (!flow_b) {
    // Lateral start uniform over one lattice cell around the axis, drawn per repetition: on a fixed
    // x = 0 the focal character would pass exactly between two columns (even column counts, never
    // touching anyone at low density) or exactly head-on with one (odd counts), an artefact of
    // the street width rather than of the density.
    Rng rng(derive_seed(condition.seed, "focal/x"));
    add(Vec2((uniform01(rng) - 0.5) * s, s + 2.0 * v0), -1.0, 1, "speed/focal");
  }

  CrowdSimulation sim(make_navigation_model(spec.crowd), agents, {}, spec.crowd.dt_s);
  ScenarioResult r;
  r.trajectories = simulate_trajectories(sim, spec.duration_s, spec.fps, heading, group);
  r.area_m2 = groups * cols * block * s;
  r.achieved_density_per_m2 = static_cast<double>(crowd_size) / r.area_m2;
  std::vector<Vec2> start(agents.size());
  for (std::size_t i = 0; i < agents.size(); ++i) start[i] = agents[i].position;
  r.min_spacing_m = min_pairwise_distance(start);
  return r;
}

}  // namespace crowdlab
