#pragma once
// The work shared by every condition that shows one crowd (crowd_key.hpp), and the four framework
// stages that make it, each described as a Stage (stage.hpp) and run by the group's StageRunner:
//   stage        outputs (in DIR/crowds/<key>/)          input hash covers
//   crowd        trajectories.csv (+ surface_trajectories.csv for manifold crowds)
//                                                        factor levels, scenario type, group seed, spec text
//   animation    baseline.glb                            spec text, MPFB2 asset folder; the crowd's recipe
//   correction   ours.glb                                damping, stiffness, contact stiffness; the bytes
//                                                        of baseline.glb
//   metrics      <method>.metrics.json                   the bytes of the animation file it measures and
//                                                        of baseline.glb (its "correction_quality" is
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
#include "framework/pipeline/stage_runner.hpp"
#include "framework/spec/condition_kinds.hpp"
#include "framework/spec/experiment_spec.hpp"

namespace crowdlab {

class CrowdGroup {
 public:
  /// `first`: the group's first condition (its crowd factors are the group's); `crowds_dir`: DIR/crowds.
  CrowdGroup(const ExperimentSpec& spec, StageRunner& runner, const std::filesystem::path& crowds_dir,
             const Condition& first);
  // Stages capture `this`: a group stays where it was made.
  CrowdGroup(const CrowdGroup&) = delete;
  CrowdGroup& operator=(const CrowdGroup&) = delete;

  const std::string& key() const { return key_; }
  const std::filesystem::path& dir() const { return dir_; }
  /// The group's condition, with the group's seed (crowd_condition()).
  const Condition& condition() const { return condition_; }

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

  const ExperimentSpec& spec_;
  StageRunner& runner_;
  std::string key_;
  std::filesystem::path dir_;
  Condition condition_;
  std::string crowd_hash_;
  bool crowd_done_ = false;
  std::optional<ScenarioResult> scenario_;
  SurfaceTrajectories surface_;
  std::array<std::optional<CrowdAnimation>, kCrowdMethodCount> animation_;
  std::array<std::optional<nlohmann::json>, kCrowdMethodCount> metrics_;
};

}  // namespace crowdlab
