#include "analysis/rm_anova.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "analysis/sphericity.hpp"
#include "framework/core/error.hpp"

namespace crowdlab::analysis {

Eigen::MatrixXd helmert_contrasts(size_t levels) {
  const auto l = static_cast<Eigen::Index>(levels);
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(l, l - 1);
  for (Eigen::Index j = 0; j < l - 1; ++j) {
    // Column j contrasts level j+1 with the mean of levels 0..j.
    const double k = static_cast<double>(j + 1);
    const double norm = std::sqrt(k * (k + 1.0));
    for (Eigen::Index i = 0; i <= j; ++i) h(i, j) = 1.0 / norm;
    h(j + 1, j) = -k / norm;
  }
  return h;
}

namespace {
Eigen::MatrixXd kron(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  Eigen::MatrixXd k(a.rows() * b.rows(), a.cols() * b.cols());
  for (Eigen::Index i = 0; i < a.rows(); ++i)
    for (Eigen::Index j = 0; j < a.cols(); ++j)
      k.block(i * b.rows(), j * b.cols(), b.rows(), b.cols()) = a(i, j) * b;
  return k;
}

}  // namespace

std::vector<std::vector<size_t>> effect_subsets(size_t k) {
  std::vector<std::vector<size_t>> out;
  for (size_t mask = 1; mask < (size_t{1} << k); ++mask) {
    std::vector<size_t> s;
    for (size_t f = 0; f < k; ++f)
      if (mask & (size_t{1} << f)) s.push_back(f);
    out.push_back(s);
  }
  std::stable_sort(out.begin(), out.end(), [](const auto& a, const auto& b) {
    if (a.size() != b.size()) return a.size() < b.size();
    return a < b;
  });
  return out;
}

Eigen::MatrixXd effect_contrasts(const WithinDesign& design, const std::vector<size_t>& effect_factors) {
  Eigen::MatrixXd c = Eigen::MatrixXd::Ones(1, 1);
  for (size_t f = 0; f < design.factors.size(); ++f) {
    const size_t l = design.factors[f].levels.size();
    const bool in_effect = std::find(effect_factors.begin(), effect_factors.end(), f) != effect_factors.end();
    const Eigen::MatrixXd m = in_effect ? helmert_contrasts(l)
                                        : Eigen::MatrixXd::Constant(static_cast<Eigen::Index>(l), 1,
                                                                    1.0 / std::sqrt(static_cast<double>(l)));
    c = kron(c, m);
  }
  return c;
}

namespace {
constexpr Eigen::Index kMinSubjects = 3;

std::string dv_location(const WithinDesign& design) {
  return (design.source.empty() ? std::string("design") : design.source) +
         (design.dv.empty() ? std::string() : ": column '" + design.dv + "'");
}

// With 2 subjects the error covariance has rank 1: Greenhouse-Geisser's epsilon is 1/d whatever the data
// and Huynh-Feldt's is 0/0, so the sphericity corrections the table reports are meaningless.
void require_enough_subjects(const WithinDesign& design) {
  const auto n = design.cell_means.rows();
  if (n < kMinSubjects)
    throw InputError((design.source.empty() ? std::string("design") : design.source) + ": " +
                     std::to_string(n) + " subjects; a repeated-measures ANOVA needs at least " +
                     std::to_string(kMinSubjects) + " (with 2 the sphericity corrections are undefined)");
}

}  // namespace

// F = MS_effect / MS_error is undefined (0/0, printed -nan) or infinite when the error term is zero:
// a constant dependent variable, or every subject showing exactly the same differences between cells.
// "Zero" is relative to the data's total variability, so rounding noise counts as zero too.
void require_error_variance(const WithinDesign& design, const RmAnovaEffect& e, double ss_total) {
  if (!(ss_total > 0)) {
    std::ostringstream value;
    value << (design.cell_means.size() ? design.cell_means(0, 0) : 0.0);
    throw InputError(dv_location(design) + ": the dependent variable is constant (every cell mean is " +
                     value.str() + "): there is no variance to analyse");
  }
  if (!(e.ss_error > 1e-12 * ss_total))
    throw InputError(dv_location(design) + ": effect '" + e.name +
                     "' has zero error variance (every subject shows the same differences between the "
                     "cells), so its F ratio is undefined");
}

void complete_effect(const WithinDesign& design, RmAnovaEffect& e, const Eigen::MatrixXd& error_ssp,
                     double error_df, double ss_total) {
  e.ss_error = error_ssp.trace();
  e.ms = e.ss / e.df1;
  e.ms_error = e.ss_error / e.df2;
  require_error_variance(design, e, ss_total);
  e.f = e.ms / e.ms_error;
  e.p = f_upper_tail(e.f, e.df1, e.df2);
  e.pes = e.ss / (e.ss + e.ss_error);
  if (error_ssp.cols() > 1)
    apply_sphericity(e, error_ssp, error_df, static_cast<double>(design.cell_means.cols()));
}

RmAnovaResult rm_anova(const WithinDesign& design) {
  if (!design.between.empty()) return mixed_anova(design);
  require_enough_subjects(design);
  const Eigen::MatrixXd& y = design.cell_means;
  const auto n = static_cast<double>(y.rows());
  const double ss_total = (y.array() - y.mean()).square().sum();
  RmAnovaResult result;
  result.subjects = static_cast<size_t>(y.rows());
  {
    const Eigen::VectorXd z = y.rowwise().sum() / std::sqrt(static_cast<double>(y.cols()));
    result.ss_subjects = (z.array() - z.mean()).square().sum();
  }
  double ss_error_total = 0;
  for (const auto& factors : effect_subsets(design.factors.size())) {
    RmAnovaEffect e;
    e.factors = factors;
    for (size_t i = 0; i < factors.size(); ++i) e.name += (i ? ":" : "") + design.factors[factors[i]].name;
    const Eigen::MatrixXd z = y * effect_contrasts(design, factors);
    const Eigen::RowVectorXd zbar = z.colwise().mean();
    const Eigen::MatrixXd centred = z.rowwise() - zbar;
    const Eigen::MatrixXd s = centred.transpose() * centred;
    const double d = static_cast<double>(z.cols());
    e.df1 = d;
    e.df2 = d * (n - 1.0);
    e.ss = n * zbar.squaredNorm();
    complete_effect(design, e, s, n - 1.0, ss_total);
    ss_error_total += e.ss_error;
    result.effects.push_back(std::move(e));
  }
  for (auto& e : result.effects) e.ges = e.ss / (e.ss + result.ss_subjects + ss_error_total);
  return result;
}

}  // namespace crowdlab::analysis
