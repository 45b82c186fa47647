#pragma once
// `crowdlab run`: every stage for every condition, incremental like a build system.
//
// Output layout (DIR = --out):
//   DIR/spec.yaml                       the spec that was run (copied for provenance)
//   DIR/crowds/<crowd key>/             work shared by conditions that show the same crowd:
//       trajectories.csv                2D trajectories (crowd stage)
//       baseline.glb                    full-body animation (animation stage)
//       ours.glb                        corrected animation (correction stage; only when a condition asks)
//       <method>.metrics.json           overlap volume, V_i, penetration depth, collisions (metrics stage)
//   DIR/conditions/<condition id>/      one folder per condition:
//       crowd.glb                       the animation this condition shows (hard link)
//       metrics.json                    its metrics (hard link)
//       clip.mp4                        the rendered stimulus (stimuli stage)
//   DIR/manifest.csv                    every stimulus (StimulusManifest); per shard when sharded
//
// The crowd key is the condition id without the render-only factor `viewpoint` and without `method`:
// every viewpoint and both methods of one design cell show the same crowd (seed 000 §4.4.1: "for each
// viewpoint-density-scenario combination, we generate an animation with and without solving
// collisions"). Its seed is derive_seed(spec.seed, "crowd/" + key).
// Every output has a provenance sidecar (provenance.hpp); a stage re-runs only when its inputs changed.
#include <filesystem>
#include <string>

#include "experiments/cli/pipeline/shard.hpp"
#include "framework/core/crowd_animation.hpp"
#include "framework/core/surface_trajectories.hpp"
#include "framework/crowd/generate_scenario.hpp"
#include "framework/spec/experiment_spec.hpp"

namespace crowdlab::cli {

struct RunOptions {
  std::filesystem::path out_dir;
  bool force = false;  ///< re-run every stage even when up to date
  Shard shard;         ///< the slice of conditions to run
  std::string only;    ///< run just this condition id ("" = all)
};

struct RunSummary {
  int conditions = 0;  ///< conditions in this run (after sharding/filtering)
  int stages_run = 0;
  int stages_skipped = 0;  ///< up to date
  std::filesystem::path manifest;
};

/// The crowd key of a condition (see header).
std::string crowd_key(const Condition& condition);

/// `condition` with the seed of its crowd group: derive_seed(spec.seed, "crowd/" + crowd_key(condition)).
Condition crowd_condition(const ExperimentSpec& spec, const Condition& condition);

/// The animation stage of `run` (baseline.glb) for one crowd group: the body model (procedural or
/// MPFB2), the motion (dancing for stationary scenarios, walking otherwise) and, for surface crowds,
/// the frames stood on the surface. `crowd_condition` carries the group's seed (crowd_condition()),
/// `scenario` is the crowd stage's result for it and `surface` is empty unless the scenario is a manifold.
CrowdAnimation animate_scenario(const ExperimentSpec& spec, const Condition& crowd_condition,
                                const std::string& key, const ScenarioResult& scenario,
                                const SurfaceTrajectories& surface);

RunSummary run_experiment(const ExperimentSpec& spec, const RunOptions& options);

}  // namespace crowdlab::cli
