#pragma once
// The animation stage of the run pipeline (baseline.glb) for one crowd group: the body model
// (procedural or MPFB2, body_model.hpp), the motion (dancing for stationary scenarios, walking
// otherwise) and, for surface crowds, the frames stood on the surface (seed 002).
//   spec             the experiment (animation section, seed)
//   crowd_condition  the group's condition, with the group's seed (crowd_condition())
//   key              the crowd key (crowd_key()), recorded as the animation's condition id
//   scenario         the crowd stage's result for it (trajectories in metres, seconds)
//   surface          the 3D frames of a manifold crowd; empty otherwise
#include <string>

#include "framework/core/crowd_animation.hpp"
#include "framework/core/surface_trajectories.hpp"
#include "framework/crowd/generate_scenario.hpp"
#include "framework/spec/experiment_spec.hpp"

namespace crowdlab {

CrowdAnimation animate_scenario(const ExperimentSpec& spec, const Condition& crowd_condition,
                                const std::string& key, const ScenarioResult& scenario,
                                const SurfaceTrajectories& surface);

}  // namespace crowdlab
