#pragma once
// The run pipeline as a library (`crowdlab run` calls it): every stage for every condition,
// incremental like a build system. Stages are data (stage.hpp) run by one StageRunner
// (stage_runner.hpp); the crowd, animation, correction and metrics stages are the crowd group's
// (crowd_group.hpp); the stages that present a condition (render, contact sheet) are contributed as
// data (PresentationStage) by the stimuli module and handed in by the composing program, so framework/
// needs no renderer. The whole table, with each stage's recipe: docs/architecture.md, "Stages".
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
//   DIR/crowds/<crowd key>/<method>.contact_sheet.png   V1-V4 at the middle frame (presentation stages)
//   DIR/manifest.csv                    every stimulus (StimulusManifest); per shard when sharded
// Every output has a provenance sidecar (provenance.hpp); a stage re-runs only when its inputs changed.
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

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
  /// The metrics stage's mesh-level overlap and proxy coverage (issue 27), about three quarters of its
  /// time on MPFB2 crowds; off only for a caller that reads neither (`reproduce gomez2024 --quick`).
  /// Part of the metrics recipe, so switching it redoes that stage.
  bool mesh_measures = true;
};

struct RunSummary {
  int conditions = 0;  ///< conditions in this run (after sharding/filtering)
  int stages_run = 0;
  int stages_skipped = 0;  ///< up to date
  std::filesystem::path manifest;
};

/// A stage that shows one condition's crowd (render, contact sheet; or `run --check-only`'s stimulus
/// check), described as data by the module that makes it (stimuli/presentation_stages.hpp) and run, in
/// table order, after the crowd group's stages. Whether the spec asks for it (outputs.video) is the
/// stage's own decision (`make`).
struct PresentationStage {
  std::string name;
  /// The stage for condition `c` of group `group`, writing into `condition_dir` (or the group's folder);
  /// nullopt when the spec does not ask for it. Asking the group for a crowd file runs its stages.
  std::function<std::optional<Stage>(CrowdGroup& group, const Condition& c,
                                     const std::filesystem::path& condition_dir)>
      make;
  /// Its main output is the condition's stimulus: the manifest entry's file and SHA-256 (its size is
  /// the spec's render.width x render.height).
  bool stimulus = false;
  /// Optional: after the stage ran (or was up to date), fills what it measured into the condition's
  /// manifest entry (the render stage's stimulus check, issue 28).
  std::function<void(const Condition& c, const std::filesystem::path& condition_dir, StimulusEntry& entry)>
      describe;
};

/// The names of the run's stages in run order: the crowd group's (crowd, animation, correction,
/// metrics), then the presentation stages (docs/architecture.md's stage table is this list).
std::vector<std::string> run_stage_names(const std::vector<PresentationStage>& presentation);

/// Runs the spec's conditions (practice first) into options.out_dir. Without presentation stages no
/// clip is made and the manifest's entries carry no file.
RunSummary run_experiment(const ExperimentSpec& spec, const RunOptions& options,
                          const std::vector<PresentationStage>& presentation = {});

}  // namespace crowdlab
