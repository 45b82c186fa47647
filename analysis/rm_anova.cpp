#include "analysis/rm_anova.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/fisher_f.hpp>
#include <cmath>
#include <sstream>
#include <string>

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

double f_upper(double f, double df1, double df2) {
  if (!(f > 0)) return 1.0;
  return boost::math::cdf(boost::math::complement(boost::math::fisher_f_distribution<double>(df1, df2), f));
}

double chisq_upper(double x, double df) {
  if (!(x > 0)) return 1.0;
  return boost::math::cdf(boost::math::complement(boost::math::chi_squared_distribution<double>(df), x));
}

// Every non-empty subset of {0..k-1}, ordered by size then lexicographically (R's term order).
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
}  // namespace

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
}  // namespace

RmAnovaResult rm_anova(const WithinDesign& design) {
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
    e.ss_error = s.trace();
    e.ms = e.ss / e.df1;
    e.ms_error = e.ss_error / e.df2;
    require_error_variance(design, e, ss_total);
    e.f = e.ms / e.ms_error;
    e.p = f_upper(e.f, e.df1, e.df2);
    e.pes = e.ss / (e.ss + e.ss_error);
    ss_error_total += e.ss_error;
    if (z.cols() > 1) {
      const double gg = s.trace() * s.trace() / (d * (s * s).trace());
      const double hf = (n * d * gg - 2.0) / (d * (n - 1.0 - d * gg));
      e.gg_eps = gg;
      e.p_gg = f_upper(e.f, gg * e.df1, gg * e.df2);
      // HF's denominator is <= 0 when n - 1 <= d eps_GG (few subjects for many cells): car then reports
      // a negative epsilon and a NaN p; here both are left empty.
      if (std::isfinite(hf) && hf > 0) {
        e.hf_eps = hf;
        const double hf_used = std::min(1.0, hf);
        e.p_hf = f_upper(e.f, hf_used * e.df1, hf_used * e.df2);
      }
      if (n - 1.0 >= d) {
        const Eigen::MatrixXd sigma = s / (n - 1.0);
        const double det = sigma.determinant();
        if (det > 0) {
          const double log_w = std::log(det) - d * std::log(sigma.trace() / d);
          const double rho = 1.0 - (2.0 * d * d + d + 2.0) / (6.0 * d * (n - 1.0));
          // R's mauchly.test.SSD (used by car/afex) writes "3 * p" with p the number of cells, not d;
          // kept for agreement (the term is O(1/n^2)).
          const double cells = static_cast<double>(y.cols());
          const double w2 = (d + 2.0) * (d - 1.0) * (d - 2.0) *
                            (2.0 * d * d * d + 6.0 * d * d + 3.0 * cells + 2.0) /
                            (288.0 * std::pow((n - 1.0) * d * rho, 2.0));
          const double zstat = -(n - 1.0) * rho * log_w;
          const double f = d * (d + 1.0) / 2.0 - 1.0;
          const double q_f = chisq_upper(zstat, f);
          e.mauchly_w = std::exp(log_w);
          e.mauchly_p = q_f + w2 * (chisq_upper(zstat, f + 4.0) - q_f);
        }
      }
    }
    result.effects.push_back(std::move(e));
  }
  for (auto& e : result.effects) e.ges = e.ss / (e.ss + result.ss_subjects + ss_error_total);
  return result;
}

}  // namespace crowdlab::analysis
