#include "analysis/sphericity.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/fisher_f.hpp>
#include <cmath>

namespace crowdlab::analysis {

double f_upper_tail(double f, double df1, double df2) {
  if (!(f > 0)) return 1.0;
  return boost::math::cdf(boost::math::complement(boost::math::fisher_f_distribution<double>(df1, df2), f));
}

namespace {
double chisq_upper(double x, double df) {
  if (!(x > 0)) return 1.0;
  return boost::math::cdf(boost::math::complement(boost::math::chi_squared_distribution<double>(df), x));
}
}  // namespace

void apply_sphericity(RmAnovaEffect& e, const Eigen::MatrixXd& s, double error_df, double cells) {
  const double d = static_cast<double>(s.cols());
  const double gg = s.trace() * s.trace() / (d * (s * s).trace());
  const double hf = ((error_df + 1.0) * d * gg - 2.0) / (d * (error_df - d * gg));
  e.gg_eps = gg;
  e.p_gg = f_upper_tail(e.f, gg * e.df1, gg * e.df2);
  // HF's denominator is <= 0 when df <= d eps_GG (few subjects for many cells): car then reports a
  // negative epsilon and a NaN p; here both are left empty.
  if (std::isfinite(hf) && hf > 0) {
    e.hf_eps = hf;
    const double hf_used = std::min(1.0, hf);
    e.p_hf = f_upper_tail(e.f, hf_used * e.df1, hf_used * e.df2);
  }
  if (error_df < d) return;
  const Eigen::MatrixXd sigma = s / error_df;
  const double det = sigma.determinant();
  if (!(det > 0)) return;
  const double log_w = std::log(det) - d * std::log(sigma.trace() / d);
  const double rho = 1.0 - (2.0 * d * d + d + 2.0) / (6.0 * d * error_df);
  // R's mauchly.test.SSD (used by car/afex) writes "3 * p" with p the number of cells, not d; kept for
  // agreement (the term is O(1/n^2)).
  const double w2 = (d + 2.0) * (d - 1.0) * (d - 2.0) * (2.0 * d * d * d + 6.0 * d * d + 3.0 * cells + 2.0) /
                    (288.0 * std::pow(error_df * d * rho, 2.0));
  const double zstat = -error_df * rho * log_w;
  const double f = d * (d + 1.0) / 2.0 - 1.0;
  const double q_f = chisq_upper(zstat, f);
  e.mauchly_w = std::exp(log_w);
  e.mauchly_p = q_f + w2 * (chisq_upper(zstat, f + 4.0) - q_f);
}

}  // namespace crowdlab::analysis
