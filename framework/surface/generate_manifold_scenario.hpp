#pragma once
// The `manifold` scenario (seed 002): a crowd walking on a 3D surface, produced for the pipeline like
// the 2D scenarios of framework/crowd/generate_scenario.hpp, plus the 3D frames the animation stage
// needs to stand the bodies on the surface.
//
// Inputs from the spec (docs/spec-reference.md):
//   scenario.mesh            scene name (surface_scenes.hpp) or .obj/.gltf/.glb path
//   crowd size               `characters` factor, else round(density * mesh area), else scenario.agents
//   crowd.model              orca | social  -> SurfaceAvoidance (ORCA or social forces, tangent plane)
//   crowd.agent_radius_m     radius of the three stacked spheres (seed 002's Offset)
//   crowd.neighbor_distance_m, crowd.max_neighbors, crowd.time_horizon_s, crowd.max_speed_mps
//   scenario.walk_speed_mps  preferred speed
//   fps, duration_s          frames = round(duration * fps)
// Choices (documented here, the paper is silent):
//   - agent height 1.8 m (the stacked spheres span feet to head; a typical adult stature);
//   - Relevant = the visibility-aware function (seed 002 §3, "ours");
//   - 8 goals drawn area-uniformly on the mesh, each agent picks one, a new one on arrival;
//   - the simulation steps at the largest dt <= crowd.dt_s that divides the frame interval 1 / fps
//     (dt = 1 / (fps * k), k = ceil(1 / (fps * crowd.dt_s))), and 1 s of warm-up precedes frame 0 so
//     that the clip starts with the crowd in motion;
//   - facing = the velocity direction while moving faster than 0.1 m/s, else the last facing.
// Randomness: derive_seed(condition.seed, "manifold").
#include "framework/core/surface_trajectories.hpp"
#include "framework/crowd/generate_scenario.hpp"

namespace crowdlab {

struct ManifoldScenario {
  ScenarioResult result;        ///< developed 2D trajectories; environment = the mesh, no ground plane
  SurfaceTrajectories surface;  ///< where each frame happens in 3D (feet, up, facing)
  int triangles = 0;
};

/// Throws InputError for a bad mesh, crowd model or parameter (naming the spec key).
ManifoldScenario generate_manifold_scenario(const ExperimentSpec& spec, const Condition& condition);

}  // namespace crowdlab
