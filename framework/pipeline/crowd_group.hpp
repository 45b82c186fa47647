#pragma once
// The work shared by every condition that shows one crowd (crowd_key.hpp), and the four framework
// stages that make it, each described as a Stage (stage.hpp) and run by the group's StageRunner. Each
// stage's compute reads its recipe (crowd_recipes.hpp) and its input files only; the group holds no
// ExperimentSpec. The input hash covers the recipe (every field), the inputs and the code version:
//   stage        outputs (in DIR/crowds/<key>/)          recipe; inputs
//   crowd        trajectories.csv (+ surface_trajectories.csv for manifold crowds)
//                                                        CrowdRecipe; the manifold mesh file
//   animation    baseline.glb                            AnimationRecipe; the crowd's recipe (upstream),
//                                                        the motion clip files
//   correction   ours.glb                                CorrectionRecipe; baseline.glb
//   metrics      <method>.metrics.json                   MetricsRecipe; the animation file it measures and
//                                                        baseline.glb (its "correction_quality" is
//                                                        measured against the baseline)
// Each result is computed (or loaded, when up to date) on first use and kept in memory while the
// group's conditions run; asking for a stage runs the stages it reads first, so no call order matters.
// Crowd files are always read back from disk after they are written (stage.hpp), so the correction,
// the metrics and the clips see the same float32 data in a fresh and in a resumed run.
// Units: trajectories in metres and seconds; metrics volumes in litres (metrics_json.hpp).
#include <array>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "framework/core/crowd_animation.hpp"
#include "framework/core/surface_trajectories.hpp"
#include "framework/crowd/generate_scenario.hpp"
#include "framework/pipeline/crowd_recipes.hpp"
#include "framework/pipeline/stage_runner.hpp"
#include "framework/spec/condition_kinds.hpp"

namespace crowdlab {

class CrowdGroup {
 public:
  /// `recipes`: crowd_group_recipes() of the group's first condition; `crowds_dir`: DIR/crowds.
  CrowdGroup(CrowdGroupRecipes recipes, StageRunner& runner, const std::filesystem::path& crowds_dir);
  // Stages capture `this`: a group stays where it was made.
  CrowdGroup(const CrowdGroup&) = delete;
  CrowdGroup& operator=(const CrowdGroup&) = delete;

  const std::string& key() const { return key_; }
  const std::filesystem::path& dir() const { return dir_; }
  const CrowdGroupRecipes& recipes() const { return recipes_; }
  /// The crowd stage's input hash: what the stages computed from its in-memory result are upstream of.
  const std::string& crowd_hash() const { return crowd_hash_; }
  /// The files of the crowd stage (trajectories.csv, surface_trajectories.csv for manifold crowds).
  std::vector<std::filesystem::path> crowd_paths() const;

  /// The crowd stage's result (computed in memory on first use; the csv files are its outputs).
  const ScenarioResult& scenario();
  /// The 3D frames of a manifold crowd; empty for crowds on the ground plane.
  const SurfaceTrajectories& surface();

  /// The animation a method shows: baseline.glb or ours.glb, made or loaded by its stage.
  const CrowdAnimation& animation(CrowdMethod method);
  std::filesystem::path animation_path(CrowdMethod method) const;

  /// The metrics stage's JSON for a method's animation (metrics_json.hpp).
  const nlohmann::json& metrics(CrowdMethod method);
  std::filesystem::path metrics_path(CrowdMethod method) const;

  /// The stages as data (exposed for tests and for the docs' stage table).
  Stage crowd_stage();
  Stage animation_stage();
  Stage correction_stage();
  Stage metrics_stage(CrowdMethod method);

 private:
  bool is_manifold() const;
  void run_crowd_stage();

  const CrowdGroupRecipes recipes_;
  StageRunner& runner_;
  std::string key_;
  std::filesystem::path dir_;
  std::string crowd_hash_;
  bool crowd_done_ = false;
  std::optional<ScenarioResult> scenario_;
  SurfaceTrajectories surface_;
  std::array<std::optional<CrowdAnimation>, kCrowdMethodCount> animation_;
  std::array<std::optional<nlohmann::json>, kCrowdMethodCount> metrics_;
};

}  // namespace crowdlab
