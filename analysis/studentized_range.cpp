#include "analysis/studentized_range.hpp"

#include <array>
#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/tools/roots.hpp>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "framework/core/error.hpp"

namespace crowdlab::analysis {
namespace {
// Fixed 10-point Gauss-Legendre rule on equal panels (Copenhaver & Holland's scheme, with more panels).
using Legendre = boost::math::quadrature::gauss<double, 10>;
constexpr int kZPanels = 17;  // unit panels over z in [-8.5, 8.5]
constexpr int kSPanels = 40;  // panels over log s

double normal_cdf(double x) {
  return 0.5 * std::erfc(-x / std::numbers::sqrt2);
}

// The inner rule's nodes, weights, phi(z) and Phi(z) do not depend on w: computed once.
struct InnerRule {
  std::array<double, 10 * kZPanels> z{}, weight_phi{}, cdf{};
  InnerRule() {
    const auto& x = Legendre::abscissa();
    const auto& wt = Legendre::weights();
    size_t n = 0;
    for (int panel = 0; panel < kZPanels; ++panel) {
      const double centre = -8.5 + panel + 0.5;
      auto add = [&](double offset, double weight) {
        z[n] = centre + 0.5 * offset;
        weight_phi[n] = 0.5 * weight * std::exp(-0.5 * z[n] * z[n]) / std::sqrt(2.0 * std::numbers::pi);
        cdf[n] = normal_cdf(z[n]);
        ++n;
      };
      for (size_t i = 0; i < x.size(); ++i) {  // Boost stores the non-negative half of the abscissae
        add(x[i], wt[i]);
        if (x[i] != 0.0) add(-x[i], wt[i]);
      }
    }
  }
};

// Range distribution of k standard normals (infinite df). The integrand is below phi(z) and so
// negligible (< 1e-17) outside |z| < 8.5; unit-width panels resolve it to ~1e-14.
double range_cdf(double w, int k) {
  if (!(w > 0)) return 0.0;
  if (w > 40.0) return 1.0;  // 1 - W_k(w) < k^2 Phi(-w / sqrt 2) underflows
  static const InnerRule rule;
  const double km1 = k - 1.0;
  double sum = 0;
  for (size_t i = 0; i < rule.z.size(); ++i) {
    const double inner = normal_cdf(rule.z[i] + w) - rule.cdf[i];
    if (inner > 0) sum += rule.weight_phi[i] * std::pow(inner, km1);
  }
  return std::min(1.0, k * sum);
}
}  // namespace

double ptukey(double q, int nmeans, double df) {
  if (nmeans < 2 || !(df > 0)) throw InputError("ptukey: need nmeans >= 2 and df > 0");
  if (!(q > 0)) return 0.0;
  if (std::isinf(q)) return 1.0;
  if (std::isinf(df)) return range_cdf(q, nmeans);
  const double half = 0.5 * df;
  const double log_norm = std::log(2.0) + half * std::log(half) - std::lgamma(half);
  auto density = [&](double s) {
    if (!(s > 0)) return 0.0;
    return std::exp(log_norm + (df - 1.0) * std::log(s) - half * s * s);
  };
  const boost::math::chi_squared_distribution<double> chi2(df);
  const double tail = 1e-18;
  const double s_lo = std::sqrt(boost::math::quantile(chi2, tail) / df);
  const double s_hi = std::sqrt(boost::math::quantile(boost::math::complement(chi2, tail)) / df);
  // Substituting s = exp(t) resolves both the density and the sigmoid W_k(q s), whose width in s
  // shrinks like 1/q, with equal panels in t.
  auto integrand = [&](double t) {
    const double sv = std::exp(t);
    return density(sv) * sv * range_cdf(q * sv, nmeans);
  };
  const double t_lo = std::log(s_lo), t_hi = std::log(s_hi), h = (t_hi - t_lo) / kSPanels;
  double value = 0;
  for (int i = 0; i < kSPanels; ++i)
    value += Legendre::integrate(integrand, t_lo + i * h, t_lo + (i + 1) * h);
  return std::clamp(value, 0.0, 1.0);
}

double qtukey(double p, int nmeans, double df) {
  if (!(p > 0 && p < 1)) throw InputError("qtukey: p must be in (0, 1), got " + std::to_string(p));
  if (nmeans < 2 || !(df > 0)) throw InputError("qtukey: need nmeans >= 2 and df > 0");
  auto f = [&](double q) { return ptukey(q, nmeans, df) - p; };
  double lo = 0.0, hi = 1.0;
  while (f(hi) < 0) {
    lo = hi;
    hi *= 2.0;
    if (hi > 1e8) throw RuntimeError("qtukey: no bracket found");
  }
  std::uintmax_t iterations = 200;
  const auto r =
      boost::math::tools::toms748_solve(f, lo, hi, boost::math::tools::eps_tolerance<double>(32), iterations);
  return 0.5 * (r.first + r.second);
}

}  // namespace crowdlab::analysis
