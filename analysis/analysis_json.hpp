#pragma once
// JSON forms of the analysis results: the stable interface of `crowdlab analyze ... --json`.
//   anova:   {"effects": [{"effect", "df1", "df2", "SS", "MS", "F", "p", "pes", "ges", "mauchly_W",
//             "mauchly_p", "gg_eps", "hf_eps", "p_gg", "p_hf"}]}; keys that do not apply are null.
//   posthoc: {"effect", "method", "levels": [...], "means": [...], "comparisons": [{"a", "b", "mean_a",
//             "mean_b", "difference", "se", "df", "statistic", "p", "p_adjusted", "simple"}]}
#include <nlohmann/json.hpp>

#include "analysis/posthoc.hpp"
#include "analysis/rm_anova.hpp"

namespace crowdlab::analysis {

nlohmann::json anova_to_json(const RmAnovaResult& result);
nlohmann::json posthoc_to_json(const PosthocResult& result);

}  // namespace crowdlab::analysis
