#include "analysis/analysis_json.hpp"

namespace crowdlab::analysis {
namespace {
nlohmann::json optional_value(const std::optional<double>& v) {
  return v.has_value() && std::isfinite(*v) ? nlohmann::json(*v) : nlohmann::json(nullptr);
}
nlohmann::json finite_or_null(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr);
}
}  // namespace

nlohmann::json anova_to_json(const RmAnovaResult& result) {
  nlohmann::json effects = nlohmann::json::array();
  for (const auto& e : result.effects) {
    effects.push_back({{"effect", e.name},
                       {"df1", e.df1},
                       {"df2", e.df2},
                       {"SS", e.ss},
                       {"MS", e.ms},
                       {"F", finite_or_null(e.f)},
                       {"p", finite_or_null(e.p)},
                       {"pes", finite_or_null(e.pes)},
                       {"ges", finite_or_null(e.ges)},
                       {"mauchly_W", optional_value(e.mauchly_w)},
                       {"mauchly_p", optional_value(e.mauchly_p)},
                       {"gg_eps", optional_value(e.gg_eps)},
                       {"hf_eps", optional_value(e.hf_eps)},
                       {"p_gg", optional_value(e.p_gg)},
                       {"p_hf", optional_value(e.p_hf)}});
  }
  return {{"subjects", result.subjects}, {"effects", effects}};
}

nlohmann::json posthoc_to_json(const PosthocResult& result) {
  nlohmann::json pairs = nlohmann::json::array();
  for (const auto& p : result.pairs)
    pairs.push_back({{"a", p.level_a},
                     {"b", p.level_b},
                     {"mean_a", p.mean_a},
                     {"mean_b", p.mean_b},
                     {"difference", p.difference},
                     {"se", finite_or_null(p.se)},
                     {"df", p.df},
                     {"statistic", finite_or_null(p.statistic)},
                     {"p", finite_or_null(p.p)},
                     {"p_adjusted", finite_or_null(p.p_adjusted)},
                     {"simple", p.simple}});
  nlohmann::json j = {{"effect", result.effect},
                      {"method", result.method == PosthocMethod::tukey ? "tukey" : "bonferroni"},
                      {"levels", result.levels},
                      {"means", result.means},
                      {"comparisons", pairs}};
  // Only with --error pooled|separate: the classic output (and the pinned report) stays as it was.
  if (result.error != PosthocError::classic)
    j["error"] = result.error == PosthocError::pooled ? "pooled" : "separate";
  return j;
}

}  // namespace crowdlab::analysis
