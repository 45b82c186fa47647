#include "analysis/posthoc.hpp"

#include <algorithm>
#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <tuple>

#include "analysis/studentized_range.hpp"
#include "framework/core/error.hpp"

namespace crowdlab::analysis {

std::vector<size_t> parse_effect(const WithinDesign& design, const std::string& effect) {
  std::vector<size_t> out;
  size_t start = 0;
  while (start <= effect.size()) {
    const size_t end = std::min(effect.find(':', start), effect.size());
    const std::string name = effect.substr(start, end - start);
    auto it =
        std::find_if(design.factors.begin(), design.factors.end(), [&](auto& f) { return f.name == name; });
    if (it == design.factors.end())
      throw InputError("effect '" + effect + "': unknown factor '" + name + "'");
    const auto idx = static_cast<size_t>(it - design.factors.begin());
    if (std::find(out.begin(), out.end(), idx) != out.end())
      throw InputError("effect '" + effect + "': factor '" + name + "' named twice");
    out.push_back(idx);
    start = end + 1;
  }
  std::sort(out.begin(), out.end());
  return out;
}

namespace {
// Index of a design cell's projection onto the effect's factors (first effect factor slowest).
size_t effect_cell(const WithinDesign& design, const std::vector<size_t>& effect_factors, size_t cell) {
  const auto levels = design.cell_levels(cell);
  size_t idx = 0;
  for (size_t f : effect_factors) idx = idx * design.factors[f].levels.size() + levels[f];
  return idx;
}

std::vector<size_t> effect_levels_of(const WithinDesign& design, const std::vector<size_t>& effect_factors,
                                     size_t idx) {
  std::vector<size_t> lv(effect_factors.size());
  for (size_t i = effect_factors.size(); i-- > 0;) {
    const size_t l = design.factors[effect_factors[i]].levels.size();
    lv[i] = idx % l;
    idx /= l;
  }
  return lv;
}
}  // namespace

Eigen::MatrixXd effect_subject_means(const WithinDesign& design, const std::vector<size_t>& effect_factors) {
  size_t m = 1;
  for (size_t f : effect_factors) m *= design.factors[f].levels.size();
  const Eigen::MatrixXd& y = design.cell_means;
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(y.rows(), static_cast<Eigen::Index>(m));
  const double per_mean = static_cast<double>(design.cell_count()) / static_cast<double>(m);
  for (size_t c = 0; c < design.cell_count(); ++c)
    out.col(static_cast<Eigen::Index>(effect_cell(design, effect_factors, c))) +=
        y.col(static_cast<Eigen::Index>(c));
  return out / per_mean;
}

double posthoc_comparison_count(const std::vector<size_t>& level_counts, bool simple_only) {
  double means = 1;
  for (size_t l : level_counts) means *= static_cast<double>(l);
  if (!simple_only) return means * (means - 1.0) / 2.0;
  double pairs = 0;
  for (size_t count : level_counts) {
    const auto l = static_cast<double>(count);
    pairs += l * (l - 1.0) / 2.0 * (means / l);
  }
  return pairs;
}

void check_posthoc_family(const WithinDesign& design, const std::string& effect,
                          const std::vector<size_t>& level_counts, bool simple_only, size_t max_comparisons) {
  const double count = posthoc_comparison_count(level_counts, simple_only);
  if (count <= static_cast<double>(max_comparisons)) return;
  throw InputError(SourceLocation{design.source, 0, 0, effect},
                   "post-hoc family of " + std::to_string(std::llround(count)) +
                       " comparisons, more than the limit of " + std::to_string(max_comparisons) +
                       " (--max-comparisons)");
}

namespace {
double t_two_sided(double t, double df) {
  return 2.0 * boost::math::cdf(
                   boost::math::complement(boost::math::students_t_distribution<double>(df), std::abs(t)));
}

// One within effect's error stratum: its orthonormal contrasts, MS_error and df2.
struct Stratum {
  Eigen::MatrixXd contrasts;
  double ms_error = 0, df = 0;
};

// SE and df of the cell contrast c (emmeans' univariate or multivariate model, see PosthocError).
std::pair<double, double> contrast_error(const WithinDesign& design, const std::vector<Stratum>& strata,
                                         const Eigen::VectorXd& c, PosthocError error) {
  const double n = static_cast<double>(design.cell_means.rows());
  if (error == PosthocError::separate) {
    const Eigen::VectorXd d = design.cell_means * c;
    const double sd = std::sqrt((d.array() - d.mean()).square().sum() / (n - 1.0));
    return {sd / std::sqrt(n), n - 1.0};
  }
  double var = 0, denom = 0;
  for (const auto& s : strata) {
    const double term = (s.contrasts.transpose() * c).squaredNorm() * s.ms_error / n;
    var += term;
    denom += term * term / s.df;
  }
  return {std::sqrt(var), var * var / denom};
}

std::vector<Stratum> error_strata(const WithinDesign& design) {
  std::vector<Stratum> out;
  for (const auto& e : rm_anova(design).effects)
    out.push_back({effect_contrasts(design, e.factors), e.ms_error, e.df2});
  return out;
}

void compare_with_error(const WithinDesign& design, const std::vector<size_t>& effect_factors,
                        const std::vector<Stratum>& strata, size_t a, size_t b, size_t means,
                        PosthocMethod method, PosthocError error, PairwiseComparison& pc) {
  Eigen::VectorXd c = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(design.cell_count()));
  const double per_mean = static_cast<double>(design.cell_count()) / static_cast<double>(means);
  for (size_t cell = 0; cell < design.cell_count(); ++cell) {
    const size_t k = effect_cell(design, effect_factors, cell);
    if (k == a) c[static_cast<Eigen::Index>(cell)] = 1.0 / per_mean;
    if (k == b) c[static_cast<Eigen::Index>(cell)] = -1.0 / per_mean;
  }
  std::tie(pc.se, pc.df) = contrast_error(design, strata, c, error);
  complete_t_comparison(pc, method, means);
}
}  // namespace

PairwiseComparison compare_means(const PosthocResult& res, size_t a, size_t b, size_t differing) {
  PairwiseComparison pc;
  pc.simple = differing == 1;
  pc.level_a = res.levels[a];
  pc.level_b = res.levels[b];
  pc.mean_a = res.means[a];
  pc.mean_b = res.means[b];
  pc.difference = pc.mean_a - pc.mean_b;
  return pc;
}

void complete_t_comparison(PairwiseComparison& pc, PosthocMethod method, size_t means) {
  pc.statistic = pc.difference / pc.se;
  pc.p = t_two_sided(pc.statistic, pc.df);
  if (method == PosthocMethod::tukey)
    pc.p_adjusted = 1.0 - ptukey(std::abs(pc.statistic) * std::sqrt(2.0), static_cast<int>(means), pc.df);
}

void adjust_family(PosthocResult& res) {
  if (res.method == PosthocMethod::bonferroni)
    for (auto& pc : res.pairs) pc.p_adjusted = std::min(1.0, pc.p * static_cast<double>(res.pairs.size()));
}

PosthocResult posthoc(const WithinDesign& design, const std::vector<size_t>& effect_factors,
                      PosthocMethod method, bool simple_only, size_t max_comparisons, PosthocError error) {
  if (effect_factors.empty()) throw InputError("posthoc: empty effect");
  std::string effect;
  std::vector<size_t> level_counts;
  for (size_t f : effect_factors) {
    effect += (effect.empty() ? "" : ":") + design.factors[f].name;
    level_counts.push_back(design.factors[f].levels.size());
  }
  check_posthoc_family(design, effect, level_counts, simple_only, max_comparisons);
  const Eigen::MatrixXd means = effect_subject_means(design, effect_factors);
  const auto m = static_cast<size_t>(means.cols());
  const double n = static_cast<double>(means.rows());
  PosthocResult res;
  res.method = method;
  res.error = error;
  res.effect = effect;
  for (size_t c = 0; c < m; ++c) {
    const auto lv = effect_levels_of(design, effect_factors, c);
    std::string label;
    for (size_t i = 0; i < lv.size(); ++i)
      label += (i ? ":" : "") + design.factors[effect_factors[i]].levels[lv[i]];
    res.levels.push_back(label);
    res.means.push_back(means.col(static_cast<Eigen::Index>(c)).mean());
  }
  // Tukey's pooled error term: the effect's row of the ANOVA.
  double ms_error = 0, df_error = 0;
  const std::vector<Stratum> strata =
      error == PosthocError::pooled ? error_strata(design) : std::vector<Stratum>{};
  if (method == PosthocMethod::tukey && error == PosthocError::classic) {
    const auto anova = rm_anova(design);
    for (const auto& e : anova.effects)
      if (e.factors == effect_factors) {
        ms_error = e.ms_error;
        df_error = e.df2;
      }
  }
  const double cells_per_mean = static_cast<double>(design.cell_count()) / static_cast<double>(m);
  for (size_t a = 0; a < m; ++a)
    for (size_t b = a + 1; b < m; ++b) {
      const auto la = effect_levels_of(design, effect_factors, a),
                 lb = effect_levels_of(design, effect_factors, b);
      size_t differing = 0;
      for (size_t i = 0; i < la.size(); ++i) differing += la[i] != lb[i];
      if (simple_only && differing != 1) continue;
      PairwiseComparison pc = compare_means(res, a, b, differing);
      if (error != PosthocError::classic) {
        compare_with_error(design, effect_factors, strata, a, b, m, method, error, pc);
      } else if (method == PosthocMethod::bonferroni) {
        const Eigen::VectorXd d =
            means.col(static_cast<Eigen::Index>(a)) - means.col(static_cast<Eigen::Index>(b));
        const double sd = std::sqrt((d.array() - d.mean()).square().sum() / (n - 1.0));
        pc.df = n - 1.0;
        pc.se = sd / std::sqrt(n);
        pc.statistic = pc.difference / pc.se;
        pc.p = pc.se > 0
                   ? 2.0 * boost::math::cdf(boost::math::complement(
                               boost::math::students_t_distribution<double>(pc.df), std::abs(pc.statistic)))
                   : (pc.difference == 0 ? 1.0 : 0.0);
      } else {
        pc.df = df_error;
        pc.se = std::sqrt(ms_error / (n * cells_per_mean));
        pc.statistic = std::abs(pc.difference) / pc.se;
        pc.p = 1.0 - ptukey(pc.statistic, static_cast<int>(m), df_error);
        pc.p_adjusted = pc.p;
      }
      res.pairs.push_back(pc);
    }
  adjust_family(res);
  return res;
}

std::vector<SimpleEffect> simple_effects(const WithinDesign& design,
                                         const std::vector<size_t>& effect_factors, size_t at_factor) {
  if (effect_factors.size() < 2 ||
      std::find(effect_factors.begin(), effect_factors.end(), at_factor) == effect_factors.end())
    throw InputError("simple effects need an interaction that contains the 'at' factor");
  std::vector<size_t> rest_original;
  for (size_t f : effect_factors)
    if (f != at_factor) rest_original.push_back(f);
  std::vector<SimpleEffect> out;
  const auto& at = design.factors[at_factor];
  for (size_t level = 0; level < at.levels.size(); ++level) {
    WithinDesign sub;
    sub.source = design.source;
    sub.dv = design.dv;
    std::vector<size_t> remap(design.factors.size(), 0);
    for (size_t f = 0; f < design.factors.size(); ++f)
      if (f != at_factor) {
        remap[f] = sub.factors.size();
        sub.factors.push_back(design.factors[f]);
      }
    sub.subjects = design.subjects;
    std::vector<Eigen::Index> cols;
    for (size_t c = 0; c < design.cell_count(); ++c)
      if (design.cell_levels(c)[at_factor] == level) cols.push_back(static_cast<Eigen::Index>(c));
    sub.cell_means.resize(design.cell_means.rows(), static_cast<Eigen::Index>(cols.size()));
    for (size_t j = 0; j < cols.size(); ++j)
      sub.cell_means.col(static_cast<Eigen::Index>(j)) = design.cell_means.col(cols[j]);
    std::vector<size_t> rest;
    for (size_t f : rest_original) rest.push_back(remap[f]);
    const auto anova = rm_anova(sub);
    for (const auto& e : anova.effects)
      if (e.factors == rest) out.push_back({at.name + "=" + at.levels[level], e});
  }
  return out;
}

std::string significance_stars(double p) {
  if (p < 0.001) return "***";
  if (p < 0.01) return "**";
  if (p < 0.05) return "*";
  return "";
}

}  // namespace crowdlab::analysis
