#include "study_ui/paired_t_test.hpp"

#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <limits>

#include "framework/core/error.hpp"

namespace crowdlab::study {

PairedTTest paired_t_test(const std::vector<double>& d) {
  if (d.size() < 2) throw InputError("paired t-test needs at least 2 participants");
  double sum = 0.0;
  for (double x : d) {
    if (!std::isfinite(x)) throw InputError("paired t-test: a difference is not finite");
    sum += x;
  }
  const double n = static_cast<double>(d.size());
  PairedTTest r;
  r.mean_difference = sum / n;
  double ss = 0.0;
  for (double x : d) ss += (x - r.mean_difference) * (x - r.mean_difference);
  const double sd = std::sqrt(ss / (n - 1.0));
  r.df = n - 1.0;
  if (sd == 0.0) {
    r.t = r.mean_difference == 0.0
              ? 0.0
              : std::copysign(std::numeric_limits<double>::infinity(), r.mean_difference);
    r.p_two_sided = r.mean_difference == 0.0 ? 1.0 : 0.0;
    r.cohens_dz = r.t;
    return r;
  }
  r.t = r.mean_difference / (sd / std::sqrt(n));
  r.cohens_dz = r.mean_difference / sd;
  const boost::math::students_t dist(r.df);
  r.p_two_sided = 2.0 * boost::math::cdf(boost::math::complement(dist, std::fabs(r.t)));
  return r;
}

}  // namespace crowdlab::study
