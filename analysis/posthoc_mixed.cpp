// Pairwise comparisons in designs with between-subject factors (`analyze posthoc --between`), as
// emmeans compares the cells of an afex::aov_ez model (Lenth, emmeans: "Models supported", mlm and
// aovlist; Maxwell & Delaney 2004, ch. 14):
// - Groups: each combination b of the between factors' levels, with n_b subjects (every combination
//   must have subjects). M_b: the group's mean of each within cell (subjects x cells averaged in b).
// - The effect's cells: its between factors' level combinations x its within factors' combinations.
//   An effect cell's mean is emmeans' estimated marginal mean: the equally weighted average, over the
//   groups and within cells that match it, of M_b (weights W_e, groups x cells; emmeans' default
//   weights = "equal", so unequal group sizes do not tilt the marginal means).
// - A comparison of cells e and f is the contrast C = W_e - W_f, estimate sum_b C_b' M_b.
// - separate (emmeans' multivariate model, afex's default): S the residual covariance of the subjects'
//   cell vectors about their group means, df N - B; Var = sum_b C_b' S C_b / n_b, df = N - B.
// - pooled (the univariate model, the aov with Error(subject / within)): strata s = the subjects
//   (Q_0 = 1/sqrt(cells), error MS of the between effects, df N - B) and each within effect E (its
//   orthonormal contrasts Q_E, error MS and df of E's row in the mixed ANOVA); Var = sum_s MS_s
//   sum_b |Q_s' C_b|^2 / n_b, Satterthwaite (1946) df = Var^2 / sum_s (term_s^2 / df_s).
// Then t = estimate / SE, p two-sided, Tukey's adjustment ptukey(|t| sqrt 2, cells, df) or Bonferroni.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <map>

#include "analysis/posthoc.hpp"
#include "framework/core/error.hpp"

namespace crowdlab::analysis {
namespace {
struct Groups {
  std::vector<std::vector<size_t>> levels;  ///< per group: the level of each between factor
  std::vector<size_t> of_subject;
  std::vector<double> size;
  Eigen::MatrixXd means;  ///< groups x cells
  Eigen::MatrixXd residual_cov;
  double df = 0;
};

Groups build_groups(const WithinDesign& design) {
  Groups g;
  size_t count = 1;
  for (const auto& f : design.between) count *= f.levels.size();
  for (size_t b = 0; b < count; ++b) {
    std::vector<size_t> lv(design.between.size());
    size_t rest = b;
    for (size_t f = design.between.size(); f-- > 0;) {
      lv[f] = rest % design.between[f].levels.size();
      rest /= design.between[f].levels.size();
    }
    g.levels.push_back(lv);
  }
  const Eigen::MatrixXd& y = design.cell_means;
  g.size.assign(count, 0.0);
  g.means = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(count), y.cols());
  for (size_t s = 0; s < design.subjects.size(); ++s) {
    const auto b = static_cast<size_t>(std::find(g.levels.begin(), g.levels.end(), design.subject_groups[s]) -
                                       g.levels.begin());
    g.of_subject.push_back(b);
    g.size[b] += 1;
    g.means.row(static_cast<Eigen::Index>(b)) += y.row(static_cast<Eigen::Index>(s));
  }
  for (size_t b = 0; b < count; ++b) {
    if (g.size[b] == 0) {
      std::string name;
      for (size_t f = 0; f < design.between.size(); ++f)
        name += (f ? ", " : "") + design.between[f].name + "=" + design.between[f].levels[g.levels[b][f]];
      throw InputError(design.source + ": no subject in the group " + name +
                       ": every combination of the between factors needs subjects for post-hoc comparisons");
    }
    g.means.row(static_cast<Eigen::Index>(b)) /= g.size[b];
  }
  g.df = static_cast<double>(design.subjects.size()) - static_cast<double>(count);
  if (g.df < 1) throw InputError(design.source + ": as many groups as subjects: no error variance left");
  Eigen::MatrixXd r = y;
  for (size_t s = 0; s < design.subjects.size(); ++s)
    r.row(static_cast<Eigen::Index>(s)) -= g.means.row(static_cast<Eigen::Index>(g.of_subject[s]));
  g.residual_cov = r.transpose() * r / g.df;
  return g;
}

// The effect's cells: (between levels of the effect's between factors, within levels of its within
// factors), the between factors first (afex's order), the last factor varying fastest.
struct EffectCells {
  std::vector<std::vector<size_t>> between, within;
  std::vector<std::string> labels;
};

EffectCells effect_cells(const WithinDesign& design, const MixedEffect& effect) {
  EffectCells cells;
  std::vector<size_t> sizes;
  for (size_t f : effect.between) sizes.push_back(design.between[f].levels.size());
  for (size_t f : effect.within) sizes.push_back(design.factors[f].levels.size());
  size_t count = 1;
  for (size_t s : sizes) count *= s;
  for (size_t c = 0; c < count; ++c) {
    std::vector<size_t> lv(sizes.size());
    size_t rest = c;
    for (size_t i = sizes.size(); i-- > 0;) {
      lv[i] = rest % sizes[i];
      rest /= sizes[i];
    }
    const auto nb = static_cast<std::ptrdiff_t>(effect.between.size());
    cells.between.emplace_back(lv.begin(), lv.begin() + nb);
    cells.within.emplace_back(lv.begin() + nb, lv.end());
    std::string label;
    for (size_t i = 0; i < effect.between.size(); ++i)
      label += (label.empty() ? "" : ":") + design.between[effect.between[i]].levels[lv[i]];
    for (size_t i = 0; i < effect.within.size(); ++i)
      label += (label.empty() ? "" : ":") + design.factors[effect.within[i]].levels[cells.within.back()[i]];
    cells.labels.push_back(label);
  }
  return cells;
}

// W_e: groups x design cells, the equal weights of the groups and within cells matching effect cell e.
Eigen::MatrixXd cell_weights(const WithinDesign& design, const MixedEffect& effect, const Groups& g,
                             const EffectCells& cells, size_t e) {
  Eigen::VectorXd group_w = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(g.levels.size()));
  for (size_t b = 0; b < g.levels.size(); ++b) {
    bool match = true;
    for (size_t i = 0; i < effect.between.size(); ++i)
      match = match && g.levels[b][effect.between[i]] == cells.between[e][i];
    group_w[static_cast<Eigen::Index>(b)] = match ? 1.0 : 0.0;
  }
  Eigen::VectorXd cell_w = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(design.cell_count()));
  for (size_t c = 0; c < design.cell_count(); ++c) {
    const auto lv = design.cell_levels(c);
    bool match = true;
    for (size_t i = 0; i < effect.within.size(); ++i)
      match = match && lv[effect.within[i]] == cells.within[e][i];
    cell_w[static_cast<Eigen::Index>(c)] = match ? 1.0 : 0.0;
  }
  return (group_w / group_w.sum()) * (cell_w / cell_w.sum()).transpose();
}

struct MixedStratum {
  Eigen::MatrixXd contrasts;  ///< cells x d, orthonormal
  double ms_error = 0, df = 0;
};

// The univariate model's strata: the subjects (the between effects' error) and each within effect.
std::vector<MixedStratum> mixed_strata(const WithinDesign& design) {
  std::map<std::vector<size_t>, MixedStratum> by_within;
  for (const auto& e : rm_anova(design).effects)
    if (!by_within.count(e.factors))
      by_within[e.factors] = {effect_contrasts(design, e.factors), e.ms_error, e.df2};
  std::vector<MixedStratum> out;
  for (auto& [factors, s] : by_within) out.push_back(std::move(s));
  return out;
}

std::pair<double, double> contrast_error(const Groups& g, const std::vector<MixedStratum>& strata,
                                         const Eigen::MatrixXd& c, PosthocError error) {
  if (error == PosthocError::separate) {
    double var = 0;
    for (Eigen::Index b = 0; b < c.rows(); ++b) {
      const Eigen::VectorXd row = c.row(b).transpose();
      const Eigen::VectorXd s_row = g.residual_cov * row;
      var += row.dot(s_row) / g.size[static_cast<size_t>(b)];
    }
    return {std::sqrt(var), g.df};
  }
  double var = 0, denom = 0;
  for (const auto& s : strata) {
    double projected = 0;
    for (Eigen::Index b = 0; b < c.rows(); ++b)
      projected +=
          (s.contrasts.transpose() * c.row(b).transpose()).squaredNorm() / g.size[static_cast<size_t>(b)];
    const double term = projected * s.ms_error;
    var += term;
    denom += term * term / s.df;
  }
  return {std::sqrt(var), var * var / denom};
}
}  // namespace

MixedEffect parse_mixed_effect(const WithinDesign& design, const std::string& effect) {
  MixedEffect out;
  size_t start = 0;
  while (start <= effect.size()) {
    const size_t end = std::min(effect.find(':', start), effect.size());
    const std::string name = effect.substr(start, end - start);
    auto named = [&](const WithinFactor& f) { return f.name == name; };
    const auto w = std::find_if(design.factors.begin(), design.factors.end(), named);
    const auto b = std::find_if(design.between.begin(), design.between.end(), named);
    std::vector<size_t>& into = w != design.factors.end() ? out.within : out.between;
    if (w == design.factors.end() && b == design.between.end())
      throw InputError("effect '" + effect + "': unknown factor '" + name + "'");
    const auto idx = static_cast<size_t>(w != design.factors.end() ? w - design.factors.begin()
                                                                   : b - design.between.begin());
    if (std::find(into.begin(), into.end(), idx) != into.end())
      throw InputError("effect '" + effect + "': factor '" + name + "' named twice");
    into.push_back(idx);
    start = end + 1;
  }
  std::sort(out.within.begin(), out.within.end());
  std::sort(out.between.begin(), out.between.end());
  return out;
}

PosthocResult posthoc_mixed(const WithinDesign& design, const MixedEffect& effect, PosthocMethod method,
                            bool simple_only, size_t max_comparisons, PosthocError error) {
  if (error == PosthocError::classic)
    throw InputError(
        "posthoc with --between: use --error separate (emmeans' multivariate model, afex's default) or "
        "--error pooled (the univariate model); classic Tukey has no single error term across strata");
  std::string name;
  std::vector<size_t> level_counts;
  for (size_t f : effect.between) {
    name += (name.empty() ? "" : ":") + design.between[f].name;
    level_counts.push_back(design.between[f].levels.size());
  }
  for (size_t f : effect.within) {
    name += (name.empty() ? "" : ":") + design.factors[f].name;
    level_counts.push_back(design.factors[f].levels.size());
  }
  check_posthoc_family(design, name, level_counts, simple_only, max_comparisons);
  const EffectCells cells = effect_cells(design, effect);
  const size_t m = cells.labels.size();
  auto differing = [&](size_t a, size_t b) {
    size_t d = 0;
    for (size_t i = 0; i < cells.between[a].size(); ++i) d += cells.between[a][i] != cells.between[b][i];
    for (size_t i = 0; i < cells.within[a].size(); ++i) d += cells.within[a][i] != cells.within[b][i];
    return d;
  };
  const Groups g = build_groups(design);
  const std::vector<MixedStratum> strata =
      error == PosthocError::pooled ? mixed_strata(design) : std::vector<MixedStratum>{};
  std::vector<Eigen::MatrixXd> weights;
  PosthocResult res;
  res.effect = name;
  res.method = method;
  res.error = error;
  for (size_t e = 0; e < m; ++e) {
    weights.push_back(cell_weights(design, effect, g, cells, e));
    res.levels.push_back(cells.labels[e]);
    res.means.push_back(weights.back().cwiseProduct(g.means).sum());
  }
  for (size_t a = 0; a < m; ++a)
    for (size_t b = a + 1; b < m; ++b) {
      const size_t d = differing(a, b);
      if (simple_only && d != 1) continue;
      PairwiseComparison pc = compare_means(res, a, b, d);
      std::tie(pc.se, pc.df) = contrast_error(g, strata, weights[a] - weights[b], error);
      complete_t_comparison(pc, method, m);
      res.pairs.push_back(pc);
    }
  adjust_family(res);
  return res;
}

}  // namespace crowdlab::analysis
