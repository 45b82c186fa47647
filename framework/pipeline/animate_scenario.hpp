#pragma once
// The animation stage of the run pipeline (baseline.glb) for one crowd group: the body model
// (procedural or MPFB2, body_model.hpp), the motion (dancing for stationary scenarios, walking
// otherwise) and, for surface crowds, the frames stood on the surface (seed 002).
//   recipe    the stage's recipe (crowd_recipes.hpp): animation section, the group's levels, seed, key
//   scenario  the crowd stage's result for it (trajectories in metres, seconds)
//   surface   the 3D frames of a manifold crowd; empty otherwise
#include "framework/core/crowd_animation.hpp"
#include "framework/core/surface_trajectories.hpp"
#include "framework/crowd/generate_scenario.hpp"
#include "framework/pipeline/crowd_recipes.hpp"

namespace crowdlab {

CrowdAnimation animate_scenario(const AnimationRecipe& recipe, const ScenarioResult& scenario,
                                const SurfaceTrajectories& surface);

}  // namespace crowdlab
