#pragma once
// Psychometric fits for a whole table of trials: one fit per (subject, condition), group summaries like
// seed 001 Table 1 (mean ± SD of the thresholds over participants, per condition) and a
// repeated-measures ANOVA of the participants' thresholds over the conditions.
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "analysis/psychometric_fit.hpp"
#include "analysis/psychometric_goodness.hpp"
#include "analysis/rm_anova.hpp"
#include "framework/core/csv.hpp"

namespace crowdlab::analysis {

struct PsychometricRequest {
  std::string subject, x, response;
  std::string by;                    ///< condition column, "" = one condition
  std::string x_transform = "none";  ///< none | cbrt (cube root, for interpenetration volumes)
  std::vector<double> probabilities = {0.5, 0.05};
  int bootstrap = 0;       ///< parametric-bootstrap replicates per fit (0 = none)
  std::uint64_t seed = 1;  ///< bootstrap streams: derive_seed(seed, "<subject>/<by>")
  PsychometricOptions options;
};

struct PsychometricRow {
  std::string subject, by;
  PsychometricFit fit;
  std::vector<double> thresholds;     ///< one per request probability
  std::vector<ThresholdInterval> ci;  ///< empty without bootstrap
  std::vector<double> x, y;           ///< the (transformed) trials, for plots
  PsychometricGoodness goodness;      ///< deviance / overdispersion check of the fit
};

struct PsychometricGroup {
  std::string by;
  std::vector<double> mean, sd;  ///< per probability, over subjects (SD with n - 1)
  size_t n = 0;
};

struct PsychometricAnalysis {
  PsychometricRequest request;
  std::vector<PsychometricRow> fits;             ///< subjects in order of appearance, conditions within
  std::vector<PsychometricGroup> groups;         ///< conditions in order of appearance
  std::optional<RmAnovaResult> threshold_anova;  ///< thresholds at probabilities[0] ~ by (>= 2 levels)
};

/// Throws InputError naming file:line and column for a missing column, a non-numeric x or response,
/// a response other than 0/1, or a negative value under the cube-root transform.
PsychometricAnalysis analyze_psychometric(const CsvTable& table, const PsychometricRequest& request);

/// {"fits": [{"subject", "by", "intercept", "slope", "thresholds": {"0.5": ...}, "ci": {...},
///   "converged", "separated", "warning", "lapse", "lapse_fitted", "lapse_at_boundary",
///   "step_not_identified", "nll", "deviance", "deviance_df", "deviance_p", "dispersion", "overdispersed"}],
///   "groups": [{"by", "n", "mean": {...}, "sd": {...}}], "anova": {...} or null}. Probabilities are keyed by
///   their shortest text ("0.5", "0.05").
nlohmann::json psychometric_to_json(const PsychometricAnalysis& analysis);

/// "0.5" for 0.5: the key used for a probability in JSON and tables.
std::string probability_key(double p);

/// Seed 001 Table 1 style Markdown: condition | n | threshold at each p as mean ± SD.
std::string psychometric_markdown_table(const PsychometricAnalysis& analysis, const std::string& unit);

}  // namespace crowdlab::analysis
