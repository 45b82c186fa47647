#pragma once
// APA-style (APA Publication Manual, 7th ed., section 6.43-6.46) text for ANOVA and post-hoc results:
// F(df1, df2) = 12.34, p = .003, eta_p^2 = .55; p < .001 below that; statistics to 2 decimals,
// p and effect sizes without a leading zero. When Mauchly's test is significant (p < .05) the
// Greenhouse-Geisser corrected dfs and p are reported (seed 000 section 4.4.3).
#include <string>

#include "analysis/clmm_fit.hpp"
#include "analysis/posthoc.hpp"
#include "analysis/rm_anova.hpp"

namespace crowdlab::analysis {

/// ".003", "< .001", "1.000" (APA: no leading zero).
std::string apa_p(double p);
/// "F(1.92, 17.31) = 40.72, p < .001, η²p = .82, η²G = .39" (GG-corrected when sphericity is violated).
std::string apa_f_sentence(const RmAnovaEffect& e);
/// A Markdown table: Effect | df | F | p | η²p | η²G | Mauchly W (p) | ε GG | ε HF | sig.
std::string anova_markdown_table(const RmAnovaResult& result);
/// A plain-text table for the terminal.
std::string anova_text_table(const RmAnovaResult& result);
/// Markdown table of pairwise comparisons.
std::string posthoc_markdown_table(const PosthocResult& result);
/// Markdown table of a CLMM's fixed effects: Term | Estimate (log cumulative odds, or probit units) |
/// SE | z | p | sig., then a line with the random-intercept SD and the log-likelihood.
std::string clmm_markdown_table(const ClmmResult& result);

}  // namespace crowdlab::analysis
