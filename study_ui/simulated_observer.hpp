#pragma once
// Simulated observers: synthetic participants that answer from each stimulus's measured metrics, for
// CI, pipeline tests and power analysis (simulate-study, power, --simulate).
//
// Perceived collision ("Did the characters go through each other?"), a logistic psychometric model
// (seed 001 §3.2, which fitted exactly this family per participant):
//   distance factor present:  P(yes) = 1 / (1 + exp((d - D_crit) / s_d))      (falls with distance d, m)
//   (unless judge_by_volume is set: then the volume rule below is used whenever a volume is known)
//   else volume known:        P(yes) = 1 / (1 + exp(-(v - V_crit) / s_v))    (rises with v, m)
//   where v = V_i (manifest v_i_m, seed 001 Eq. 1: mean cube root of overlap volume over colliding
//   frames) or, when only the per-character overlap volume is known, v = cbrt(overlap_l / 1000).
//   D_crit, V_crit population means per shoulder level are seed 001 Table 1 (D_crit 0.52/0.41/0.27 m,
//   V_crit 0.043/0.058/0.075 m for shoulder 0/1/2); each observer draws their own threshold
//   ~ N(mean, sd) (Table 1's SDs are 0.01-0.03 m and 0.004-0.008 m) and their own scale s
//   ~ mean * exp(N(0, slope_log_sd)). A lapse rate mixes in random key presses.
//   With no distance and no volume, P(yes) = logistic(-L) from the latent realism below.
// Likert and rating answers, a latent-realism model (one latent variable per trial, Thurstonian):
//   L = mu_observer + sum of level effects (default method=ours: +0.8, seed 000 §4.4.4 found
//       "Ours" rated more realistic on all three composites) + shoulder_effect * shoulder level
//       + trigger_effect * trigger/100 (seed 001 §4.3: shoulder motions raise naturalness)
//       - overlap_weight * cbrt(overlap_l) (realism falls with overlap, seed 000 Fig. 9)
//       - collision_weight * P(collision perceived) (seed 001 §3.3: naturalness correlates
//         negatively with perceived collisions) + N(0, trial_noise_sd)
//   item answer: z = L + N(0, item_noise_sd), negated for negative items (reverse-keyed ones, and items
//   whose id or text mentions collisions, e.g. seed 001 §4.2.2 "How often did you see collisions
//   between characters?", which specs keep unreversed as its own dependent variable); a k-point answer is
//   1 + floor(k * logistic(z)) (clamped to 1..k). Each observer scales every effect by their own
//   factor ~ N(1, effect_sd_fraction) (observer noise).
// Response times: stimulus onset to the first answer, then between answers, each lognormal with
// median rt_median_ms and log-sd rt_log_sd (response times are classically right-skewed, roughly
// lognormal; Luce 1986).
// These are plausible generative models for testing and planning, not fitted to the papers' raw data.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "framework/core/seed.hpp"
#include "framework/core/stimulus_manifest.hpp"
#include "study_ui/presenter.hpp"
#include "study_ui/study_question.hpp"

namespace crowdlab::study {

struct ObserverModel {
  std::map<std::string, double> d_crit_m = {{"0", 0.52}, {"1", 0.41}, {"2", 0.27}};  ///< by shoulder level
  double d_crit_sd_m = 0.03;
  double d_scale_m = 0.03;
  std::map<std::string, double> v_crit_m = {{"0", 0.043}, {"1", 0.058}, {"2", 0.075}};
  double v_crit_sd_m = 0.007;
  double v_scale_m = 0.008;
  double slope_log_sd = 0.25;
  double lapse = 0.02;
  double realism_mean = 0.3;
  double realism_sd = 0.5;
  std::map<std::string, double> level_effects = {{"method=ours", 0.8}};  ///< "factor=level" -> shift
  double shoulder_effect = 0.3;
  double trigger_effect = 0.6;
  double overlap_weight = 1.2;
  double collision_weight = 2.5;
  double trial_noise_sd = 0.5;
  double item_noise_sd = 0.5;
  double effect_sd_fraction = 0.3;
  double rt_median_ms = 1500.0;
  double rt_log_sd = 0.35;
  /// Answer the collision question from the clip's volume even when it has a distance factor (seed
  /// 001 Table 1's V_crit recovered from observers who judge by volume; key judge_by_volume=0|1).
  bool judge_by_volume = false;

  /// Sets one parameter from "key=value" (keys as the field names; level effects as
  /// "effect.FACTOR.LEVEL=shift", thresholds as "d_crit.LEVEL=m" / "v_crit.LEVEL=m").
  /// Throws InputError on an unknown key or a bad number.
  void set(const std::string& assignment);
};

/// One observer's own parameters, drawn around the model's means.
struct Observer {
  std::uint64_t seed = 0;
  std::map<std::string, double> d_crit_m, v_crit_m;
  double d_scale_m = 0.03, v_scale_m = 0.008;
  double mu = 0.0;
  double effect_gain = 1.0;
};

Observer draw_observer(const ObserverModel& model, std::uint64_t seed);

/// Probability that `observer` reports a collision for `stimulus` (without lapses); negative when the
/// stimulus has no distance or volume to judge from. judge_by_volume: see ObserverModel.
double collision_probability(const Observer& observer, const StimulusEntry& stimulus,
                             bool judge_by_volume = false);

/// One answer per question for one presentation of `stimulus`, deterministic in `rng`.
std::vector<Answer> simulate_answers(const ObserverModel& model, const Observer& observer,
                                     const StimulusEntry& stimulus,
                                     const std::vector<StudyQuestion>& questions, Rng& rng);

}  // namespace crowdlab::study
