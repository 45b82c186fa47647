#pragma once
// The collision-correction benchmark (seed 000 §3 solver on a stationary swaying crowd,
// framework/correction/swaying_crowd_fixture.hpp): median ms per Corrector::step. Shared by
// `crowdlab bench correct` and the timing table of `crowdlab reproduce gomez2024`.
#include <nlohmann/json.hpp>

#include "framework/correction/corrector_params.hpp"
#include "framework/metrics/correction_quality.hpp"

namespace crowdlab::cli {

struct CorrectBenchOptions {
  int characters = 60;
  double density = 6.66;  ///< characters per m^2
  int steps = 100;        ///< timed steps
  int warmup = 10;        ///< untimed steps first
  int threads = 0;        ///< TBB threads, 0 = all cores
  CorrectorParams params;
  bool quality = false;  ///< also measure the correction quality of the timed steps (untimed)
};

struct CorrectBenchResult {
  CorrectBenchOptions options;
  int threads = 0;  ///< resolved thread count
  double ms_median = 0, ms_mean = 0;
  double cpu_ms_median = 0;  ///< process CPU time per step, all threads (not counting waits for a core)
  double contacts_mean = 0, inter_body_contacts_mean = 0, body_pairs_mean = 0, cg_iterations_mean = 0;
  double pulling_contacts_mean = 0, active_set_passes_mean = 0;
  double deep_contacts_mean = 0, depenetration_passes_mean = 0;  ///< what the depenetration pass did
  int rejected_steps = 0, unconverged_steps = 0;
  double peak_rss_mb = 0;  ///< of the whole process so far (VmHWM), fixture animation included
  // With options.quality only: the timed steps against the fixture's input (the warm-up settles the
  // input's own initial interpenetration, so it is left out).
  double overlap_baseline_l = 0, overlap_corrected_l = 0;  ///< mean per-character overlap (litres)
  CorrectionQuality quality;
};

/// Throws InputError for characters < 1, steps < 1, warmup < 0 or threads < 0.
CorrectBenchResult run_correct_bench(const CorrectBenchOptions& options);

/// One JSON object: ms_per_step_median, ms_per_step_mean, characters, density_per_m2, steps,
/// contacts_mean, inter_body_contacts_mean, body_pairs_mean, cg_iterations_mean, rejected_steps,
/// unconverged_steps, peak_rss_mb, peak_rss_mb_per_character, threads, cpu_ms_per_step_median,
/// pulling_contacts_mean, active_set_passes_mean, deep_contacts_mean, depenetration_passes_mean; with
/// options.quality also overlap_baseline_l,
/// overlap_corrected_l, overlap_reduction, depth_p99_m, depth_max_m, rotation_dev_mean_deg,
/// rotation_dev_p99_deg, foot_skate_max_m, joint_speed_max_mps.
nlohmann::json correct_bench_json(const CorrectBenchResult& result);

}  // namespace crowdlab::cli
