#include "analysis/kolmogorov_smirnov.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <boost/math/distributions/normal.hpp>
#include <cmath>
#include <numbers>

#include "framework/core/error.hpp"

namespace crowdlab::analysis {
namespace {
// Matrix power by squaring with a shared power-of-10 exponent (MTW 2003, section 3).
void matrix_power(const Eigen::MatrixXd& a, int n, Eigen::MatrixXd& out, int& exponent) {
  if (n == 1) {
    out = a;
    exponent = 0;
    return;
  }
  Eigen::MatrixXd half;
  int e = 0;
  matrix_power(a, n / 2, half, e);
  out = half * half;
  exponent = 2 * e;
  if (n % 2 == 1) out = a * out;
  const auto m = out.rows();
  if (out(m / 2, m / 2) > 1e140) {
    out *= 1e-140;
    exponent += 140;
  }
}
}  // namespace

double kolmogorov_cdf_exact(int n, double d) {
  if (n < 1) throw InputError("kolmogorov_cdf_exact: n must be >= 1");
  if (d <= 0.5 / n) return 0.0;  // D_n >= 1/(2n) always
  if (d >= 1.0) return 1.0;
  const int k = static_cast<int>(n * d) + 1;
  const int m = 2 * k - 1;
  const double h = k - n * d;
  Eigen::MatrixXd hm(m, m);
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j) hm(i, j) = (i - j + 1 < 0) ? 0.0 : 1.0;
  for (int i = 0; i < m; ++i) {
    hm(i, 0) -= std::pow(h, i + 1);
    hm(m - 1, i) -= std::pow(h, m - i);
  }
  hm(m - 1, 0) += (2.0 * h - 1.0 > 0) ? std::pow(2.0 * h - 1.0, m) : 0.0;
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j)
      if (i - j + 1 > 0)
        for (int g = 1; g <= i - j + 1; ++g) hm(i, j) /= g;
  Eigen::MatrixXd q;
  int exponent = 0;
  matrix_power(hm, n, q, exponent);
  double s = q(k - 1, k - 1);
  for (int i = 1; i <= n; ++i) {
    s = s * i / n;
    if (s < 1e-140) {
      s *= 1e140;
      exponent -= 140;
    }
  }
  return std::clamp(s * std::pow(10.0, exponent), 0.0, 1.0);
}

double kolmogorov_cdf_asymptotic(double x) {
  if (!(x > 0)) return 0.0;
  if (x < 1.0) {
    const double pi2 = std::numbers::pi * std::numbers::pi;
    double sum = 0;
    for (int j = 1; j <= 20; ++j) {
      const double t = (2.0 * j - 1.0);
      sum += std::exp(-t * t * pi2 / (8.0 * x * x));
    }
    return std::sqrt(2.0 * std::numbers::pi) / x * sum;
  }
  double sum = 0;
  for (int j = 1; j <= 100; ++j) {
    const double term = std::exp(-2.0 * j * j * x * x);
    sum += (j % 2 ? 1.0 : -1.0) * term;
    if (term < 1e-18) break;
  }
  return 1.0 - 2.0 * sum;
}

KsResult ks_test(std::vector<double> sample, const std::function<double(double)>& cdf, int exact) {
  if (sample.empty()) throw InputError("ks_test: empty sample");
  for (double v : sample)
    if (!std::isfinite(v)) throw InputError("ks_test: non-finite value in sample");
  std::sort(sample.begin(), sample.end());
  const auto n = static_cast<int>(sample.size());
  double d = 0;
  for (int i = 0; i < n; ++i) {
    const double f = cdf(sample[static_cast<size_t>(i)]);
    d = std::max({d, f - static_cast<double>(i) / n, static_cast<double>(i + 1) / n - f});
  }
  KsResult r;
  r.statistic = d;
  r.exact = exact == 1 || (exact == -1 && n < 100);
  r.p = r.exact ? 1.0 - kolmogorov_cdf_exact(n, d) : 1.0 - kolmogorov_cdf_asymptotic(std::sqrt(n) * d);
  r.p = std::clamp(r.p, 0.0, 1.0);
  return r;
}

NormalityCheck normality_check(const std::vector<double>& values) {
  const auto n = values.size();
  if (n < 3) throw InputError("normality_check: need at least 3 values");
  double mean = 0;
  for (double v : values) mean += v;
  mean /= static_cast<double>(n);
  double ss = 0;
  for (double v : values) ss += (v - mean) * (v - mean);
  const double sd = std::sqrt(ss / static_cast<double>(n - 1));
  NormalityCheck out;
  for (double v : values) out.sample.push_back(sd > 0 ? (v - mean) / sd : 0.0);
  std::sort(out.sample.begin(), out.sample.end());
  const boost::math::normal_distribution<double> normal;
  out.ks = ks_test(out.sample, [&](double x) { return boost::math::cdf(normal, x); });
  // R's ppoints: (i - a) / (n + 1 - 2a), a = 3/8 for n <= 10, else 1/2.
  const double a = n <= 10 ? 0.375 : 0.5;
  for (size_t i = 1; i <= n; ++i)
    out.theoretical.push_back(boost::math::quantile(
        normal, (static_cast<double>(i) - a) / (static_cast<double>(n) + 1.0 - 2.0 * a)));
  return out;
}

}  // namespace crowdlab::analysis
