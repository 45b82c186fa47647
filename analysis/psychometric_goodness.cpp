#include "analysis/psychometric_goodness.hpp"

#include <boost/math/distributions/chi_squared.hpp>
#include <cmath>
#include <limits>
#include <map>

namespace crowdlab::analysis {
namespace {
// k ln(k / m), with 0 ln 0 = 0.
double xlogx_over(double k, double m) {
  return k > 0 ? k * std::log(k / m) : 0.0;
}
}  // namespace

PsychometricGoodness psychometric_goodness(const std::vector<double>& x, const std::vector<double>& y,
                                           const PsychometricFit& fit, int parameters) {
  std::map<double, std::pair<double, double>> levels;  // x -> (trials, yes)
  for (size_t i = 0; i < x.size(); ++i) {
    auto& l = levels[x[i]];
    l.first += 1.0;
    l.second += y[i];
  }
  PsychometricGoodness g;
  for (const auto& [level, counts] : levels) {
    const auto [n, k] = counts;
    const double p = fit.probability(level);
    g.deviance += 2.0 * (xlogx_over(k, n * p) + xlogx_over(n - k, n * (1.0 - p)));
  }
  g.df = static_cast<int>(levels.size()) - parameters;
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  if (g.df <= 0) {
    g.p = g.dispersion = nan;
    return g;
  }
  g.dispersion = g.deviance / g.df;
  g.p = g.deviance > 0 ? boost::math::cdf(boost::math::complement(
                             boost::math::chi_squared_distribution<double>(g.df), g.deviance))
                       : 1.0;
  g.overdispersed = g.p < 0.05;
  return g;
}

}  // namespace crowdlab::analysis
