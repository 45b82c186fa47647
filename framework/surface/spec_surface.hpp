#pragma once
// The surface a manifold spec walks on, loaded and checked as one step that both `validate` and the
// surface stage of `run` take, so that they refuse the same specs with the same message (issue 33):
//   - the mesh (a built-in scene or an .obj/.gltf/.glb file): its problems name the spec's
//     scenario.mesh line and column as well as the mesh file's own place;
//   - the crowd on it: density x mesh area for each density level (or the characters factor, or
//     scenario.agents), counted in double before any agent is placed, against kMaxCharactersPerCrowd and
//     kMaxCharacterFrames (framework/spec/work_limits.hpp, estimated by framework/spec/estimate_work.hpp): a
//     density of 0.1 on a 1 km OBJ overflowed an int and was reported as "agents: must be >= 1" although the
//     spec asked for 20 agents.
#include "framework/spec/experiment_spec.hpp"
#include "framework/surface/surface_mesh.hpp"

namespace crowdlab {

/// make_surface_scene(spec.scenario.mesh), its InputErrors prefixed with the spec's scenario.mesh place.
SurfaceMesh load_spec_surface(const ExperimentSpec& spec);

/// Refuses (InputError at the spec's factors key) a crowd on `mesh` past the work limits
/// (crowd_limit_problem with largest_crowd_on_area).
void check_surface_crowd_limits(const ExperimentSpec& spec, const SurfaceMesh& mesh);

}  // namespace crowdlab
