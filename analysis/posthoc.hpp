#pragma once
// Pairwise comparisons after a repeated-measures ANOVA, for a main effect or an interaction's cells,
// and simple effects within interactions.
//
// Means: each subject's mean over the cells of the other factors (marginal means), one per level
// combination of the effect's factors.
// - Bonferroni: paired t-tests on the subjects' differences (df = n - 1, two-sided), p multiplied by
//   the number of comparisons in the family and capped at 1 (Maxwell & Delaney 2004, ch. 11-12).
// - Tukey HSD: the pooled-error version used for within-subject designs by Statistica and textbooks
//   (Maxwell & Delaney 2004, ch. 12; Howell, Statistical Methods for Psychology, ch. 14): the effect's
//   error term MS_err and df2 from rm_anova, SE of a mean = sqrt(MS_err / (n r)) with r the number of
//   cells averaged per mean, q = |difference| / SE, p = 1 - ptukey(q, number of means, df2).
// Family: all pairs of means, or with simple_only the pairs that differ in exactly one factor (the
// comparisons within each level of the other factors, "simple" comparisons).
#include <string>
#include <vector>

#include "analysis/rm_anova.hpp"

namespace crowdlab::analysis {

enum class PosthocMethod { bonferroni, tukey };

/// The error term of each comparison (`analyze posthoc --error`):
/// - classic (the default, unchanged): Tukey with the effect's own MS_error and df2 (see above), or
///   Bonferroni paired t-tests;
/// - pooled: emmeans' univariate model (afex include_aov, `model = "univariate"`): a contrast c of the
///   cell means has variance sum over within effects E of |C_E' c|^2 MS_err(E) / n (the error strata
///   pooled by the contrast's projections), df by Satterthwaite (1946): V^2 / sum_E (term_E^2 / df2_E);
/// - separate: emmeans' multivariate model: each contrast's own error, the subjects' contrast scores
///   (SE = sd / sqrt(n), df = n - 1).
/// With pooled or separate, the statistic is t, `p` the unadjusted two-sided p and `p_adjusted` Tukey's
/// (ptukey(|t| sqrt 2, means, df), emmeans' default for pairs) or Bonferroni's by `method`.
enum class PosthocError { classic, pooled, separate };

struct PairwiseComparison {
  std::string level_a, level_b;                   ///< level names joined with ':' in effect-factor order
  double mean_a = 0, mean_b = 0, difference = 0;  ///< difference = mean_a - mean_b
  double se = 0, df = 0;
  double statistic = 0;   ///< t (Bonferroni) or q (Tukey)
  double p = 0;           ///< unadjusted (Bonferroni, pooled, separate), Tukey-adjusted (classic Tukey)
  double p_adjusted = 0;  ///< Bonferroni: min(1, p * family size); Tukey: == p
  bool simple = false;    ///< the two means differ in exactly one factor
};

struct PosthocResult {
  std::string effect;
  PosthocMethod method = PosthocMethod::bonferroni;
  PosthocError error = PosthocError::classic;
  std::vector<std::string> levels;  ///< the effect's cells, first factor slowest
  std::vector<double> means;        ///< grand means of those cells
  std::vector<PairwiseComparison> pairs;
};

/// `effect` names factors joined with ':' ("A" or "A:B"); throws InputError when a name is unknown.
std::vector<size_t> parse_effect(const WithinDesign& design, const std::string& effect);

/// subjects x (cells of the effect): each subject's mean over the other factors.
Eigen::MatrixXd effect_subject_means(const WithinDesign& design, const std::vector<size_t>& effect_factors);

/// Default bound on the comparisons of one post-hoc family (`analyze posthoc --max-comparisons`), so a
/// wrong --effect (an id column, thousands of levels: millions of pairs) is refused at once instead of
/// running for minutes. Tukey's p for m means costs about m times more than for a few (ptukey integrates
/// over the range of m normals): 4950 pairs of 100 means took 33 s on a loaded 2-core machine, so the
/// default family is 1000 (45 levels). Documented in docs/analysis.md ("Limits").
inline constexpr size_t kDefaultMaxComparisons = 1000;

/// The family's size, computed from the level counts l_f of the effect's factors (within and between)
/// alone: all pairs of the effect's m = prod l_f means, m(m-1)/2, or with simple_only the pairs
/// differing in one factor, sum over f of C(l_f, 2) * m / l_f.
double posthoc_comparison_count(const std::vector<size_t>& level_counts, bool simple_only);

/// Throws InputError naming the design's CSV, the effect (`effect`, factor names joined with ':') and
/// the family's size when it has more than max_comparisons comparisons; called before any work.
void check_posthoc_family(const WithinDesign& design, const std::string& effect,
                          const std::vector<size_t>& level_counts, bool simple_only, size_t max_comparisons);

/// Throws InputError (naming the design's CSV, the effect and the count) when the family has more than
/// max_comparisons comparisons; checked before any work.
PosthocResult posthoc(const WithinDesign& design, const std::vector<size_t>& effect_factors,
                      PosthocMethod method, bool simple_only = false,
                      size_t max_comparisons = kDefaultMaxComparisons,
                      PosthocError error = PosthocError::classic);

/// Pair a < b of `res`'s means: levels, means and difference filled in, `simple` from `differing` (the
/// number of factors in which the two cells differ); the test's fields are left to the caller.
PairwiseComparison compare_means(const PosthocResult& res, size_t a, size_t b, size_t differing);

/// t = difference / se, its two-sided p with pc.df, and Tukey's adjustment for a family of `means` means
/// (ptukey(|t| sqrt 2, means, df), emmeans' default for pairs) when `method` is Tukey.
void complete_t_comparison(PairwiseComparison& pc, PosthocMethod method, size_t means);

/// Bonferroni: p_adjusted = min(1, p x family size) for every pair (no-op for Tukey).
void adjust_family(PosthocResult& res);

/// An effect of a design with between-subject factors: indices into WithinDesign::between and ::factors.
struct MixedEffect {
  std::vector<size_t> between, within;
};

/// `effect` names within and between factors joined with ':' ("A", "G", "A:G"); throws InputError when a
/// name is unknown or repeated.
MixedEffect parse_mixed_effect(const WithinDesign& design, const std::string& effect);

/// Pairwise comparisons of an effect's cells in a design with between factors, as emmeans compares an
/// afex model's cells (posthoc_mixed.cpp): `separate` = the multivariate model (df = subjects - groups),
/// `pooled` = the univariate model (strata pooled, Satterthwaite df); `classic` is refused (InputError).
/// Cells are labelled between levels first ("lab:low"), as afex names effects. The family size is
/// checked against max_comparisons before any work.
PosthocResult posthoc_mixed(const WithinDesign& design, const MixedEffect& effect, PosthocMethod method,
                            bool simple_only = false, size_t max_comparisons = kDefaultMaxComparisons,
                            PosthocError error = PosthocError::separate);

/// One simple effect: the ANOVA of the effect's other factors at one level of `at_factor`.
struct SimpleEffect {
  std::string at;        ///< "B=b1"
  RmAnovaEffect effect;  ///< the remaining factors' effect within that level
};
/// For an interaction, the remaining factors' effect at each level of `at_factor` (one of its factors),
/// from an RM-ANOVA of the design restricted to that level.
std::vector<SimpleEffect> simple_effects(const WithinDesign& design,
                                         const std::vector<size_t>& effect_factors, size_t at_factor);

/// "***" (p < .001), "**" (< .01), "*" (< .05), "" otherwise: the papers' notation.
std::string significance_stars(double p);

}  // namespace crowdlab::analysis
