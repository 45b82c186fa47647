#pragma once
// Pieces shared by `crowdlab reproduce gomez2024` and `crowdlab reproduce hoyet2016`: the size of a
// run (full or --quick), running a paper spec through the real pipeline (`crowdlab run`, without
// video: the reproductions need the crowds and their metrics, not the clips), and a simulated study
// (`crowdlab simulate-study`) on its manifest.
#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "framework/core/stimulus_manifest.hpp"
#include "framework/spec/experiment_spec.hpp"
#include "study_ui/simulated_observer.hpp"

namespace crowdlab::cli {

/// Command-line options of both reproductions. Zero means "the size's default".
struct ReproduceOptions {
  std::string out;
  bool quick = false;        ///< the reduced CI size (documented per reproduction)
  double duration_s = 0;     ///< clip length override
  double fps = 0;            ///< frame-rate override
  int observers = 0;         ///< simulated participants
  int repetitions = 0;       ///< hoyet2016: repetitions of each pair condition
  bool force = false;        ///< recompute every pipeline stage
  bool skip_timing = false;  ///< gomez2024: leave out the timing table
};

/// A paper spec run through run_experiment() in dir/<name>/ (spec variant in dir/specs/<name>.yaml).
struct SpecRun {
  ExperimentSpec spec;
  std::filesystem::path spec_path;
  std::filesystem::path run_dir;
  StimulusManifest manifest;
};

/// Writes the variant of `yaml_text` (outputs.video and contact_sheet off, then `edit`) and runs every
/// stage but rendering for every condition (incremental: a second call reuses what is up to date).
/// `mesh_measures` false leaves the metrics' mesh-level measures out (RunOptions::mesh_measures).
/// `stimulus_check`: also `run --check-only`'s stage, its geometry only (render.check.overlap_every_frames
/// 0: the overlap columns need drawn frames), into the manifest entries' `check`.
SpecRun run_spec_variant(const std::string& yaml_text, const std::filesystem::path& dir,
                         const std::string& name, bool force,
                         const std::function<void(YAML::Node& root)>& edit, bool mesh_measures = true,
                         bool stimulus_check = false);

/// The metrics JSON (metrics_json.hpp) of one manifest entry of a SpecRun.
nlohmann::json entry_metrics(const SpecRun& run, const StimulusEntry& entry);

/// A simulated study of `observers` participants on the run's manifest (study dir is replaced), then
/// the full analysis report (`crowdlab analyze report`) in report_dir. Returns the report path.
std::string simulate_study_and_report(const SpecRun& run, const study::ObserverModel& model, int observers,
                                      std::uint64_t seed, const std::filesystem::path& study_dir,
                                      const std::filesystem::path& report_dir);

}  // namespace crowdlab::cli
