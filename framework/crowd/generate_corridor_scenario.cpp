// Corridor scenario (seed 000 §4.1/§4.4: "walking animations for densities 2.2 to 6.6 persons/m^2
// going through a narrow corridor", trajectories from RVO). Choices where the paper is silent:
//   * the corridor is scenario.width_m wide (x) and runs along +Z; the crowd initially fills
//     width x depth_m (the density's area) with N Poisson-disk positions whose centres keep one disc
//     radius from the walls, so nobody starts inside a wall;
//   * everyone walks toward +Z at walk_speed_mps x (1 + 0.05 N(0,1)) (clamped to +-10 %), so the
//     flow stays a flow but neighbours still interact; agents are already walking at t = 0 (a crowd
//     starting from rest would stretch out while it accelerates, changing the density on screen);
//   * the disc radius is min(crowd.agent_radius_m, 0.45 d_hex, 0.49 x the placement's minimum
//     spacing), d_hex = sqrt(2 A / (sqrt(3) N)) the hexagonal-packing spacing: at
//     6.6 per m^2 the centres are ~0.4 m apart, and a collision-free navigation model could not hold
//     that density with 0.25 m discs; the residual 3D collisions of seed 000 come from bodies being
//     larger than these discs. The radius used is stored per agent in the trajectories;
//   * walls: two segments at x = +-width/2 from 2 m behind the crowd to 5 m beyond where the leaders
//     can reach, also returned as 0.1 m thick, 1.2 m high boxes (crowd barriers) for rendering and
//     the physics corrector.
#include <algorithm>
#include <cmath>

#include "framework/core/seed.hpp"
#include "framework/crowd/generate_scenario.hpp"
#include "framework/crowd/make_navigation_model.hpp"
#include "framework/crowd/place_poisson_disk.hpp"
#include "framework/crowd/simulate_trajectories.hpp"

namespace crowdlab {

ScenarioResult generate_corridor_scenario(const ExperimentSpec& spec, const Condition& condition) {
  const ScenarioSpec& sc = spec.scenario;
  const double w = sc.width_m, len = sc.depth_m;
  const int n = scenario_character_count(spec, condition, w * len);
  const double d_hex = std::sqrt(2.0 * w * len / (std::sqrt(3.0) * n));
  // The disc radius is capped so that the placement's spacing can hold it (see above); centres keep
  // one radius from the walls, so nobody starts inside a wall.
  const double radius_cap = std::min(spec.crowd.agent_radius_m, 0.45 * d_hex);
  const Polygon2 area = rectangle_polygon(w - 2.0 * radius_cap, len);
  PlacementOptions opt;
  opt.min_spacing_m = spec.crowd.agent_radius_m;  // as for the stationary crowd: else InputError
  opt.personal_space_m = spec.crowd.personal_space_m;
  const Placement placement = place_poisson_disk(area, n, derive_seed(condition.seed, "placement"), opt);
  const double radius = std::min(radius_cap, 0.49 * placement.min_spacing_m);

  const double v0 = sc.walk_speed_mps;
  const double z_end = 0.5 * len + 1.2 * v0 * spec.duration_s + 5.0;
  std::vector<ObstacleSegment> walls = {{Vec2(-0.5 * w, -0.5 * len - 2.0), Vec2(-0.5 * w, z_end)},
                                        {Vec2(0.5 * w, -0.5 * len - 2.0), Vec2(0.5 * w, z_end)}};
  std::vector<AgentInit> agents(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    Rng rng(derive_seed(condition.seed, "speed/" + std::to_string(i)));
    AgentInit& a = agents[static_cast<std::size_t>(i)];
    a.position = placement.positions[static_cast<std::size_t>(i)];
    a.goal = Vec2(a.position.x(), z_end + 100.0);
    a.radius_m = radius;
    a.preferred_speed_mps = v0 * std::clamp(1.0 + 0.05 * standard_normal(rng), 0.9, 1.1);
    a.max_speed_mps = std::max(spec.crowd.max_speed_mps, a.preferred_speed_mps);
    a.velocity = Vec2(0.0, a.preferred_speed_mps);  // already walking when the clip starts
  }
  CrowdSimulation sim(make_navigation_model(spec.crowd), agents, walls, spec.crowd.dt_s);
  ScenarioResult r;
  r.trajectories =
      simulate_trajectories(sim, spec.duration_s, spec.fps, std::vector<double>(agents.size(), 0.0),
                            std::vector<int>(agents.size(), 0));
  for (const ObstacleSegment& s : walls) {
    Box b;
    const double thickness = 0.1, height = 1.2;
    const double side = s.a.x() < 0 ? -1.0 : 1.0;
    b.center_m = Vec3(s.a.x() + side * 0.5 * thickness, 0.5 * height, 0.5 * (s.a.y() + s.b.y()));
    b.half_extents_m = Vec3(0.5 * thickness, 0.5 * height, 0.5 * (s.b.y() - s.a.y()));
    r.environment.boxes.push_back(b);
  }
  r.area_m2 = w * len;
  r.achieved_density_per_m2 = n / r.area_m2;
  r.min_spacing_m = placement.min_spacing_m;
  return r;
}

}  // namespace crowdlab
