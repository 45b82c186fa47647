#include "study_ui/simulated_observer.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>

#include "framework/core/error.hpp"

namespace crowdlab::study {
namespace {

double logistic(double x) {
  return 1.0 / (1.0 + std::exp(-x));
}

double parse_number(const std::string& text, const std::string& key) {
  double v = 0.0;
  auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc() || ptr != text.data() + text.size() || !std::isfinite(v))
    throw InputError(SourceLocation{"", 0, 0, key}, "not a finite number: '" + text + "'");
  return v;
}

std::string factor_level(const StimulusEntry& e, const std::string& factor) {
  auto it = e.factors.find(factor);
  return it == e.factors.end() ? std::string() : it->second;
}

bool numeric_level(const StimulusEntry& e, const std::string& factor, double& value) {
  const std::string text = factor_level(e, factor);
  if (text.empty()) return false;
  auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  return ec == std::errc() && ptr == text.data() + text.size() && std::isfinite(value);
}

double threshold_for(const std::map<std::string, double>& by_level, const std::string& level) {
  auto it = by_level.find(level.empty() ? "0" : level);
  if (it != by_level.end()) return it->second;
  return by_level.empty() ? 0.0 : by_level.begin()->second;  // unknown level: the no-shoulder value
}

bool mentions_collisions(const StudyQuestion& q) {
  std::string t = q.id + " " + q.text;
  std::transform(t.begin(), t.end(), t.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return t.find("collision") != std::string::npos;
}

}  // namespace

void ObserverModel::set(const std::string& assignment) {
  const size_t eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InputError(SourceLocation{"", 0, 0, "--observer"}, "expected key=value, got '" + assignment + "'");
  const std::string key = assignment.substr(0, eq);
  const double v = parse_number(assignment.substr(eq + 1), key);
  auto starts = [&](const char* prefix) { return key.rfind(prefix, 0) == 0; };
  if (starts("effect.")) {
    const std::string rest = key.substr(7);
    const size_t dot = rest.find('.');
    if (dot == std::string::npos || dot == 0 || dot + 1 == rest.size())
      throw InputError(SourceLocation{"", 0, 0, key}, "expected effect.FACTOR.LEVEL=shift");
    level_effects[rest.substr(0, dot) + "=" + rest.substr(dot + 1)] = v;
    return;
  }
  if (starts("d_crit.")) {
    d_crit_m[key.substr(7)] = v;
    return;
  }
  if (starts("v_crit.")) {
    v_crit_m[key.substr(7)] = v;
    return;
  }
  if (key == "judge_by_volume") {
    if (v != 0.0 && v != 1.0) throw InputError(SourceLocation{"", 0, 0, key}, "expected 0 or 1");
    judge_by_volume = v == 1.0;
    return;
  }
  const std::map<std::string, double*> fields = {{"d_crit_sd_m", &d_crit_sd_m},
                                                 {"d_scale_m", &d_scale_m},
                                                 {"v_crit_sd_m", &v_crit_sd_m},
                                                 {"v_scale_m", &v_scale_m},
                                                 {"slope_log_sd", &slope_log_sd},
                                                 {"lapse", &lapse},
                                                 {"realism_mean", &realism_mean},
                                                 {"realism_sd", &realism_sd},
                                                 {"shoulder_effect", &shoulder_effect},
                                                 {"trigger_effect", &trigger_effect},
                                                 {"overlap_weight", &overlap_weight},
                                                 {"collision_weight", &collision_weight},
                                                 {"trial_noise_sd", &trial_noise_sd},
                                                 {"item_noise_sd", &item_noise_sd},
                                                 {"effect_sd_fraction", &effect_sd_fraction},
                                                 {"rt_median_ms", &rt_median_ms},
                                                 {"rt_log_sd", &rt_log_sd}};
  auto it = fields.find(key);
  if (it == fields.end()) throw InputError(SourceLocation{"", 0, 0, key}, "unknown observer-model parameter");
  const bool must_be_positive = key.find("scale") != std::string::npos || key == "rt_median_ms";
  if ((must_be_positive && v <= 0) ||
      (key != "realism_mean" && key != "shoulder_effect" && key != "trigger_effect" &&
       key != "overlap_weight" && key != "collision_weight" && v < 0) ||
      (key == "lapse" && v > 1))
    throw InputError(SourceLocation{"", 0, 0, key}, "value out of range: " + assignment.substr(eq + 1));
  *it->second = v;
}

Observer draw_observer(const ObserverModel& m, std::uint64_t seed) {
  Observer o;
  o.seed = seed;
  Rng rng(derive_seed(seed, "observer"));
  for (const auto& [level, mean] : m.d_crit_m)
    o.d_crit_m[level] = mean + m.d_crit_sd_m * standard_normal(rng);
  for (const auto& [level, mean] : m.v_crit_m)
    o.v_crit_m[level] = std::max(1e-4, mean + m.v_crit_sd_m * standard_normal(rng));
  o.d_scale_m = m.d_scale_m * std::exp(m.slope_log_sd * standard_normal(rng));
  o.v_scale_m = m.v_scale_m * std::exp(m.slope_log_sd * standard_normal(rng));
  o.mu = m.realism_mean + m.realism_sd * standard_normal(rng);
  o.effect_gain = std::max(0.0, 1.0 + m.effect_sd_fraction * standard_normal(rng));
  return o;
}

double collision_probability(const Observer& o, const StimulusEntry& s, bool judge_by_volume) {
  const std::string shoulder = factor_level(s, "shoulder");
  double d = 0.0;
  const bool volume_known = s.v_i_m >= 0 || s.mean_overlap_l >= 0;
  if (!(judge_by_volume && volume_known) && numeric_level(s, "distance", d))
    return logistic(-(d - threshold_for(o.d_crit_m, shoulder)) / o.d_scale_m);
  double v = -1.0;
  if (s.v_i_m >= 0)
    v = s.v_i_m;
  else if (s.mean_overlap_l >= 0)
    v = std::cbrt(s.mean_overlap_l / 1000.0);
  if (v < 0) return -1.0;
  return logistic((v - threshold_for(o.v_crit_m, shoulder)) / o.v_scale_m);
}

std::vector<Answer> simulate_answers(const ObserverModel& m, const Observer& o, const StimulusEntry& s,
                                     const std::vector<StudyQuestion>& questions, Rng& rng) {
  const double p_collision = collision_probability(o, s, m.judge_by_volume);
  double effects = 0.0;
  for (const auto& [key, shift] : m.level_effects) {
    const size_t eq = key.find('=');
    if (factor_level(s, key.substr(0, eq)) == key.substr(eq + 1)) effects += shift;
  }
  double level = 0.0;
  if (numeric_level(s, "shoulder", level)) effects += m.shoulder_effect * level;
  if (numeric_level(s, "trigger", level)) effects += m.trigger_effect * level / 100.0;
  if (s.mean_overlap_l >= 0) effects -= m.overlap_weight * std::cbrt(s.mean_overlap_l);
  if (p_collision >= 0) effects -= m.collision_weight * p_collision;
  const double latent = o.mu + o.effect_gain * effects + m.trial_noise_sd * standard_normal(rng);

  std::vector<Answer> answers;
  double rt = 0.0;
  for (const StudyQuestion& q : questions) {
    Answer a;
    a.question_id = q.id;
    if (q.kind == QuestionKind::yesno) {
      const double p = p_collision >= 0 ? p_collision : logistic(-latent);
      const double p_yes = m.lapse * 0.5 + (1.0 - m.lapse) * p;
      a.raw = uniform01(rng) < p_yes ? 1 : 0;
    } else {
      double z = latent + m.item_noise_sd * standard_normal(rng);
      if (q.reverse || mentions_collisions(q)) z = -z;  // a negative item: agreement falls with realism
      const int k = q.points;
      a.raw = std::clamp(1 + static_cast<int>(std::floor(k * logistic(z))), 1, k);
      if (uniform01(rng) < m.lapse)
        a.raw = 1 + static_cast<int>(uniform_index(rng, static_cast<std::uint64_t>(k)));
    }
    rt += m.rt_median_ms * std::exp(m.rt_log_sd * standard_normal(rng));
    a.rt_ms = rt;
    answers.push_back(std::move(a));
  }
  return answers;
}

}  // namespace crowdlab::study
