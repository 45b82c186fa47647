#pragma once
// `crowdlab analyze report`: a complete Markdown report with figures from a study's response CSVs
// (see study_responses.hpp for the format) and the spec the study ran:
//  - composites: the spec's protocol.composites, each the per-trial mean of its (reverse-coded)
//    items, with the items' internal reliability (Pearson r, Cronbach's alpha; seed 000 section 4.4.3);
//    scale questions in no composite are analysed on their own;
//  - for every such measure, the RM-ANOVA over the spec factors that vary in the data (APA table and
//    sentences, Mauchly, GG/HF), a Kolmogorov-Smirnov check of the residuals (Q-Q data written as CSV),
//    a cumulative link mixed model of each Likert item beside it (ordinal::clmm's model, logit link,
//    the factors categorical, a random intercept per participant; its table and stats/<measure>.json
//    "clmm"), Tukey post-hocs of the significant effects, and interaction plots (x = each factor, one line
//    per level of the last factor, ±1 SD error bars, stars from the simple effect of the last factor at each
//    x level);
//  - for yes/no questions with a numeric factor (distance, or the first numeric factor with >= 3
//    levels): per-participant psychometric fits by condition (the other factors), seed 001 Table 1,
//    the RM-ANOVA of the 50 % thresholds and psychometric curves (seed 001 Figure 5 style).
// Participants x Likert items are limited (work_limits.hpp, `--max-participant-items`): each item's
// model has a random intercept per participant.
// Writes <out>/report.md, <out>/figures/*.png|svg, <out>/stats/*.json|csv. Returns the report path.
#include <string>

#include "framework/spec/work_limits.hpp"

namespace crowdlab::analysis {

/// Refuses (InputError, before any model is fitted or file written) a study whose participants x Likert
/// items exceed `max_participant_items` (framework/spec/estimate_work.hpp, report_limit_problem).
std::string write_study_report(const std::string& study_dir, const std::string& spec_path,
                               const std::string& out_dir,
                               double max_participant_items = kMaxReportParticipantItems);

}  // namespace crowdlab::analysis
