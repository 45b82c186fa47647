#pragma once
// estimate_power: power of a within-subject contrast by simulated studies (Monte Carlo power
// analysis). For every sample size n and every simulation s, n fresh simulated observers answer every
// test stimulus once (practice excluded, order irrelevant to the model); each observer's score is the
// mean reverse-coded answer of the dependent variable (a question id, or a composite: the mean of its
// items after reverse coding, seed 000 §4.4.3) over the stimuli at level B of the contrast factor minus
// the mean over level A; a paired t-test (paired_t_test.hpp) on those n differences is significant
// when p < alpha. Power = fraction of significant simulations. This is deliberately minimal: the
// full analysis (RM-ANOVA, corrections) is the analysis/ stage's job, not study_ui's.
#include <cstdint>
#include <string>
#include <vector>

#include "framework/core/stimulus_manifest.hpp"
#include "framework/spec/experiment_spec.hpp"
#include "study_ui/simulated_observer.hpp"

namespace crowdlab::study {

struct PowerOptions {
  std::string factor;   ///< contrast factor, e.g. "method"
  std::string level_a;  ///< reference level, e.g. "baseline"
  std::string level_b;  ///< tested level, e.g. "ours"
  std::string dv;       ///< question or composite id ("" = first composite, else first question)
  std::vector<int> sample_sizes = {10, 20, 30};
  int simulations = 200;
  double alpha = 0.05;
  std::uint64_t seed = 1;
};

struct PowerRow {
  int n = 0;
  double power = 0.0;            ///< fraction of simulations with p < alpha
  double mean_difference = 0.0;  ///< mean over simulations of mean(B - A), dv units
  double mean_cohens_dz = 0.0;   ///< mean over simulations
  int simulations = 0;
};

/// Throws InputError when the factor or a level is absent from the manifest, the dv is unknown, or a
/// sample size is < 2.
std::vector<PowerRow> estimate_power(const ExperimentSpec& spec, const StimulusManifest& manifest,
                                     const ObserverModel& model, const PowerOptions& options);

}  // namespace crowdlab::study
