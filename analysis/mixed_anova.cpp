// Mixed (split-plot) and between-subjects ANOVA with Type III sums of squares, as afex::aov_ez (type 3)
// through car::Anova on a multivariate linear model (Fox & Weisberg 2019, ch. 5.9; O'Brien & Kaiser
// 1985; Maxwell & Delaney 2004, ch. 14):
// - Y: subjects x within cells (cell means). X: subjects x p, the intercept and every between term
//   (main effects and interactions) in sum-to-zero coding (R's contr.sum, which afex sets), so that
//   Type III hypotheses are the usual ones with unequal group sizes. B = (X'X)^-1 X'Y, residuals
//   R = Y - X B, error df = n - p.
// - For each within term W (the subjects' mean first, then the within effects in R's term order) with
//   orthonormal contrasts C_W (cells x d), and each between term T (intercept first): the hypothesis
//   SSP H = (B_T C_W)' [(X'X)^-1]_TT^-1 (B_T C_W), the error SSP E = (R C_W)'(R C_W);
//   SS = tr H, SS_error = tr E, df1 = df_T d, df2 = (n - p) d (the univariate tests of car's summary).
// - Effects are listed in that order (within outer, between inner), named between factors first, as
//   afex: treatment, gender, treatment:gender, phase, treatment:phase, ...
// - pes = SS / (SS + SS_error); ges = SS / (SS + the sum of every stratum's error SS) (Olejnik & Algina
//   2003 with every factor manipulated; afex's default `observed = NULL`).
// - Sphericity (d > 1) from E with error df n - p: sphericity.hpp. Every effect of a stratum W shares
//   its epsilons and Mauchly's test, as in car.
#include <Eigen/Dense>
#include <cmath>
#include <string>

#include "analysis/rm_anova.hpp"
#include "framework/core/error.hpp"

namespace crowdlab::analysis {
namespace {
// R's contr.sum for l levels: l x (l-1), level i < l-1 -> unit vector i, the last level -> all -1.
Eigen::MatrixXd sum_contrasts(size_t levels) {
  const auto l = static_cast<Eigen::Index>(levels);
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(l, l - 1);
  c.topRows(l - 1).setIdentity();
  c.row(l - 1).setConstant(-1.0);
  return c;
}

struct BetweenModel {
  Eigen::MatrixXd x;                            ///< subjects x p
  std::vector<std::vector<Eigen::Index>> cols;  ///< columns of each term, [0] = the intercept
  std::vector<std::vector<size_t>> terms;       ///< factor subsets, [0] = {} (intercept)
};

// The sum-coded design matrix of the between factors: for a term, the product of its factors' coding
// columns (the first factor varying fastest, as R's model.matrix; Type III SS do not depend on it).
BetweenModel between_model(const WithinDesign& design) {
  BetweenModel m;
  const auto n = static_cast<Eigen::Index>(design.subjects.size());
  std::vector<Eigen::VectorXd> columns = {Eigen::VectorXd::Ones(n)};
  m.terms.push_back({});
  m.cols.push_back({0});
  for (const auto& term : effect_subsets(design.between.size())) {
    std::vector<Eigen::VectorXd> block = {Eigen::VectorXd::Ones(n)};
    for (size_t f : term) {
      const Eigen::MatrixXd coding = sum_contrasts(design.between[f].levels.size());
      std::vector<Eigen::VectorXd> next;
      for (Eigen::Index k = 0; k < coding.cols(); ++k)
        for (const auto& prev : block) {
          Eigen::VectorXd v(n);
          for (Eigen::Index i = 0; i < n; ++i)
            v[i] = prev[i] *
                   coding(static_cast<Eigen::Index>(design.subject_groups[static_cast<size_t>(i)][f]), k);
          next.push_back(v);
        }
      block = std::move(next);
    }
    m.terms.push_back(term);
    m.cols.emplace_back();
    for (auto& v : block) {
      m.cols.back().push_back(static_cast<Eigen::Index>(columns.size()));
      columns.push_back(std::move(v));
    }
  }
  m.x.resize(n, static_cast<Eigen::Index>(columns.size()));
  for (size_t j = 0; j < columns.size(); ++j) m.x.col(static_cast<Eigen::Index>(j)) = columns[j];
  return m;
}

std::string source_of(const WithinDesign& design) {
  return design.source.empty() ? std::string("design") : design.source;
}

// Every combination of the between factors' levels needs a subject (Type III hypotheses are not
// estimable with an empty cell), and the residual df must be at least 2 (with 1 the error covariance
// has rank 1, as with 2 subjects in a within design).
void require_estimable(const WithinDesign& design, const Eigen::MatrixXd& xtx, Eigen::Index p) {
  Eigen::FullPivLU<Eigen::MatrixXd> lu(xtx);
  if (lu.rank() < p)
    throw InputError(source_of(design) +
                     ": a combination of the between-subject factors' levels has no subject (an empty "
                     "group); Type III tests need every group");
  const auto n = static_cast<Eigen::Index>(design.subjects.size());
  if (n - p < 2)
    throw InputError(source_of(design) + ": " + std::to_string(n) + " subjects for " + std::to_string(p) +
                     " between-subject parameters; the ANOVA needs at least " + std::to_string(p + 2) +
                     " (2 residual degrees of freedom)");
}

std::string effect_name(const WithinDesign& design, const std::vector<size_t>& between,
                        const std::vector<size_t>& within) {
  std::string name;
  for (size_t f : between) name += (name.empty() ? "" : ":") + design.between[f].name;
  for (size_t f : within) name += (name.empty() ? "" : ":") + design.factors[f].name;
  return name;
}
}  // namespace

RmAnovaResult mixed_anova(const WithinDesign& design) {
  const Eigen::MatrixXd& y = design.cell_means;
  const BetweenModel model = between_model(design);
  const Eigen::Index p = model.x.cols();
  const Eigen::MatrixXd xtx = model.x.transpose() * model.x;
  require_estimable(design, xtx, p);
  const Eigen::MatrixXd xtx_inv = xtx.ldlt().solve(Eigen::MatrixXd::Identity(p, p));
  const Eigen::MatrixXd coef = xtx_inv * (model.x.transpose() * y);
  const Eigen::MatrixXd resid = y - model.x * coef;
  const double error_df = static_cast<double>(y.rows() - p);
  const double ss_total = (y.array() - y.mean()).square().sum();
  RmAnovaResult result;
  result.subjects = static_cast<size_t>(y.rows());
  std::vector<std::vector<size_t>> within_terms = {{}};
  for (auto& t : effect_subsets(design.factors.size())) within_terms.push_back(t);
  double ss_error_strata = 0;
  for (const auto& w : within_terms) {
    const Eigen::MatrixXd c = effect_contrasts(design, w);
    const Eigen::MatrixXd coef_w = coef * c;
    const Eigen::MatrixXd r = resid * c;
    const Eigen::MatrixXd s = r.transpose() * r;
    const double d = static_cast<double>(c.cols());
    ss_error_strata += s.trace();
    if (w.empty()) result.ss_subjects = s.trace();
    for (size_t t = 0; t < model.terms.size(); ++t) {
      if (w.empty() && t == 0) continue;  // the grand mean
      const auto& cols = model.cols[t];
      const auto q = static_cast<Eigen::Index>(cols.size());
      Eigen::MatrixXd bt(q, c.cols()), m(q, q);
      for (Eigen::Index i = 0; i < q; ++i) {
        bt.row(i) = coef_w.row(cols[static_cast<size_t>(i)]);
        for (Eigen::Index j = 0; j < q; ++j)
          m(i, j) = xtx_inv(cols[static_cast<size_t>(i)], cols[static_cast<size_t>(j)]);
      }
      RmAnovaEffect e;
      e.factors = w;
      e.between = model.terms[t];
      e.name = effect_name(design, e.between, w);
      e.df1 = static_cast<double>(q) * d;
      e.df2 = error_df * d;
      e.ss = (bt.transpose() * m.ldlt().solve(bt)).trace();
      complete_effect(design, e, s, error_df, ss_total);
      result.effects.push_back(std::move(e));
    }
  }
  for (auto& e : result.effects) e.ges = e.ss / (e.ss + ss_error_strata);
  return result;
}

}  // namespace crowdlab::analysis
