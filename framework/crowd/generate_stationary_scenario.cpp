// Stationary (concert) scenario, seed 000 §4.1: characters keep their global position; the animation
// layer makes them dance. Choices where the paper is silent:
//   * area: scenario.width_m x depth_m centred on the origin; N Poisson-disk positions
//     (place_poisson_disk), so 9 m^2 at 2.22..6.66 per m^2 holds 20..60 characters; centres must
//     end up at least crowd.agent_radius_m apart, else InputError (N too large for the area);
//   * stage: a club stage, 1.0 m high, 3 m deep and 8 m (or twice the area) wide, whose near edge is
//     3 m beyond the area's front edge in the stage direction (stage_direction_deg, 0 = +Z): far enough
//     that a front camera (V1) stands between stage and crowd instead of looking over the stage's edge;
//   * sway: each root moves on a small Lissajous path, amplitude 2-4 cm (<= 10 % of the spacing)
//     and 0.2-0.5 Hz, a typical in-place weight shift of standing/dancing people (postural sway of
//     standing adults is centimetres; Winter 1995, "Human balance and posture control");
//   * heading: toward a point on the stage's axis 2.25 m beyond the area's front edge (so everyone faces the
//     stage), plus a slow +-5..15 degree look-around oscillation;
//   * loops: every sway and look-around frequency is rounded to a whole number of cycles over the clip
//     (possibly none: a still offset), so the last frame flows into the first when the clip loops
//     (issue 28; the dances fit their tempo the same way, dance_animation.hpp).
#include <cmath>
#include <numbers>

#include "framework/core/seed.hpp"
#include "framework/crowd/generate_scenario.hpp"
#include "framework/crowd/place_poisson_disk.hpp"
#include "framework/crowd/simulate_trajectories.hpp"

namespace crowdlab {
namespace {

/// `hz` rounded to a whole number of cycles over `duration_s` (0 when less than half a cycle fits).
double loop_frequency(double hz, double duration_s) {
  return duration_s > 0.0 ? std::round(hz * duration_s) / duration_s : hz;
}

}  // namespace

ScenarioResult generate_stationary_scenario(const ExperimentSpec& spec, const Condition& condition) {
  const ScenarioSpec& sc = spec.scenario;
  const Polygon2 area = rectangle_polygon(sc.width_m, sc.depth_m);
  const int n = scenario_character_count(spec, condition, sc.width_m * sc.depth_m);
  // Centres at least one disc radius apart: discs may overlap by up to half (residual collisions are
  // what the studies need), but a request denser than that is an input error, not a crowd.
  PlacementOptions opt;
  opt.min_spacing_m = spec.crowd.agent_radius_m;
  opt.personal_space_m = spec.crowd.personal_space_m;
  const Placement placement = place_poisson_disk(area, n, derive_seed(condition.seed, "placement"), opt);

  const double theta = sc.stage_direction_deg * std::numbers::pi / 180.0;
  const Vec2 forward(std::sin(theta), std::cos(theta));  // (x, z)
  // Distance from the centre to the area's edge along `forward` (rectangle support function).
  const double reach = 0.5 * (std::fabs(forward.x()) * sc.width_m + std::fabs(forward.y()) * sc.depth_m);
  const double stage_depth = 3.0, stage_height = 1.0, stage_gap = 3.0;
  const Vec2 stage_center = forward * (reach + stage_gap + 0.5 * stage_depth);
  // Where the dancers look: a point on the stage's axis 2.25 m beyond the area's front edge (the centre of
  // the smaller stage before issue 28, so the crowd, its animation and metrics stay what they were).
  const Vec2 focus = forward * (reach + 2.25);

  ScenarioResult r;
  Box stage;
  stage.center_m = Vec3(stage_center.x(), 0.5 * stage_height, stage_center.y());
  stage.half_extents_m =
      Vec3(std::max(4.0, std::max(sc.width_m, sc.depth_m)), 0.5 * stage_height, 0.5 * stage_depth);
  stage.rotation = Quat(Eigen::AngleAxisd(theta, Vec3::UnitY()));
  r.environment.boxes.push_back(stage);

  const int frames = std::max(1, static_cast<int>(std::lround(spec.duration_s * spec.fps)));
  const double sway_cap = std::isfinite(placement.min_spacing_m) ? 0.1 * placement.min_spacing_m : 0.04;
  r.trajectories.fps = spec.fps;
  r.trajectories.agents.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    Rng rng(derive_seed(condition.seed, "sway/" + std::to_string(i)));
    const double amp = std::min(0.02 + 0.02 * uniform01(rng), sway_cap);
    const double clip_s = frames / spec.fps;
    const double fx = loop_frequency(0.2 + 0.3 * uniform01(rng), clip_s);
    const double fz = loop_frequency(0.2 + 0.3 * uniform01(rng), clip_s);
    const double px = 2.0 * std::numbers::pi * uniform01(rng), pz = 2.0 * std::numbers::pi * uniform01(rng);
    const double look_amp = (5.0 + 10.0 * uniform01(rng)) * std::numbers::pi / 180.0;
    const double look_f = loop_frequency(0.05 + 0.1 * uniform01(rng), clip_s);
    const double look_p = 2.0 * std::numbers::pi * uniform01(rng);
    const Vec2 base = placement.positions[static_cast<std::size_t>(i)];
    const Vec2 to_stage = focus - base;
    const double facing = heading_of(to_stage.x(), to_stage.y());
    AgentTrajectory& a = r.trajectories.agents[static_cast<std::size_t>(i)];
    a.radius_m = spec.crowd.agent_radius_m;
    a.group = 0;
    a.position_m.resize(static_cast<std::size_t>(frames));
    a.heading_rad.resize(static_cast<std::size_t>(frames));
    for (int f = 0; f < frames; ++f) {
      const double t = f / spec.fps;
      const double w = 2.0 * std::numbers::pi * t;
      a.position_m[static_cast<std::size_t>(f)] =
          base + Vec2(amp * std::sin(w * fx + px), 0.5 * amp * std::sin(w * fz + pz));
      a.heading_rad[static_cast<std::size_t>(f)] = facing + look_amp * std::sin(w * look_f + look_p);
    }
  }
  r.area_m2 = placement.area_m2;
  r.achieved_density_per_m2 = placement.density_per_m2;
  r.min_spacing_m = placement.min_spacing_m;
  return r;
}

}  // namespace crowdlab
