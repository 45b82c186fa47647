#pragma once
// simulate_study: a complete synthetic data set in exactly the format of real sessions: for each of
// n observers S001..Snnn, run_session() with a SimulatedPresenter writes Sxxx.csv + Sxxx.json, and
// the per-participant CSVs are concatenated (one header) into DIR/responses.csv.
// Observer i's seed is derive_seed(seed, "observer:" + id), so the data set is reproducible and
// adding observers leaves the earlier ones unchanged. The per-trial fsync of real sessions is skipped
// (the data set is regenerable from its seed); the merged file is still written atomically.
#include <cstdint>
#include <string>

#include "framework/core/stimulus_manifest.hpp"
#include "framework/spec/experiment_spec.hpp"
#include "study_ui/simulated_observer.hpp"

namespace crowdlab::study {

struct SimulateStudyOptions {
  int observers = 30;
  std::uint64_t seed = 1;
  std::string stimuli_dir;
  std::string out_dir;
  bool verify_files = true;
};

/// Returns the path of the merged responses.csv. Throws InputError when out_dir already holds
/// participant files (a data set is never overwritten silently).
std::string simulate_study(const ExperimentSpec& spec, const StimulusManifest& manifest,
                           const ObserverModel& model, const SimulateStudyOptions& options);

/// "S001".."Snnn": the simulated participant id of observer i (0-based), zero-padded to 3 digits.
std::string simulated_participant_id(int i);

}  // namespace crowdlab::study
