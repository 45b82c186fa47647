#pragma once
// The run pipeline as a library (`crowdlab run` calls it): every stage for every condition,
// incremental like a build system. Stages are data (stage.hpp) run by one StageRunner
// (stage_runner.hpp); the crowd, animation, correction and metrics stages are the crowd group's
// (crowd_group.hpp); the stages that present a condition (render, contact sheet) come from the
// composing program through PresentationStages, so framework/ needs no renderer.
//
// Output layout (DIR = RunOptions::out_dir):
//   DIR/spec.yaml                       the spec that was run (copied for provenance)
//   DIR/crowds/<crowd key>/             work shared by conditions that show the same crowd:
//       trajectories.csv                2D trajectories (crowd stage)
//       baseline.glb                    full-body animation (animation stage)
//       ours.glb                        corrected animation (correction stage; only when a condition asks)
//       <method>.metrics.json           overlap volume, V_i, penetration depth, collisions (metrics stage)
//   DIR/conditions/<condition id>/      one folder per condition:
//       crowd.glb                       the animation this condition shows (hard link)
//       metrics.json                    its metrics (hard link)
//       clip.mp4                        the rendered stimulus (presentation stages)
//   DIR/manifest.csv                    every stimulus (StimulusManifest); per shard when sharded
// Every output has a provenance sidecar (provenance.hpp); a stage re-runs only when its inputs changed.
#include <filesystem>
#include <string>

#include "framework/core/stimulus_manifest.hpp"
#include "framework/pipeline/crowd_group.hpp"
#include "framework/pipeline/shard.hpp"
#include "framework/pipeline/stage_runner.hpp"
#include "framework/spec/experiment_spec.hpp"

namespace crowdlab {

struct RunOptions {
  std::filesystem::path out_dir;
  bool force = false;                                       ///< re-run every stage even when up to date
  Shard shard;                                              ///< the slice of conditions to run
  std::string only;                                         ///< run just this condition id ("" = all)
  nlohmann::json libraries = framework_library_versions();  ///< recorded in every provenance sidecar
};

struct RunSummary {
  int conditions = 0;  ///< conditions in this run (after sharding/filtering)
  int stages_run = 0;
  int stages_skipped = 0;  ///< up to date
  std::filesystem::path manifest;
};

/// The stages that show a condition's crowd (render, contact sheet), run after the framework stages
/// when the spec asks for video (outputs.video).
class PresentationStages {
 public:
  virtual ~PresentationStages() = default;
  /// Runs the presentation stages of condition `c` (of crowd group `group`) through `runner`, writing
  /// into `condition_dir`, and fills the stimulus fields of `entry` (file relative to `out_dir`,
  /// width, height, sha256).
  virtual void run(StageRunner& runner, CrowdGroup& group, const Condition& c,
                   const std::filesystem::path& out_dir, const std::filesystem::path& condition_dir,
                   StimulusEntry& entry) = 0;
};

/// Runs the spec's conditions (practice first) into options.out_dir. `presentation` may be null: then
/// no clip is made and the manifest's entries carry no file.
RunSummary run_experiment(const ExperimentSpec& spec, const RunOptions& options,
                          PresentationStages* presentation);

}  // namespace crowdlab
