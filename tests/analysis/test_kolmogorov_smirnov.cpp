// Kolmogorov distribution values and the KS test against R's ks.test (tests/data/analysis/ref_ks.csv).
#include <boost/math/distributions/normal.hpp>
#include <catch2/catch.hpp>
#include <sstream>

#include "analysis/kolmogorov_smirnov.hpp"
#include "analysis/reliability.hpp"
#include "framework/core/error.hpp"
#include "tests/analysis/reference_table.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_kolmogorov_smirnov {

using namespace crowdlab;
using namespace crowdlab::analysis;
using crowdlab::test::analysis_data;
using crowdlab::test::ref_number;

TEST_CASE("analysis: exact Kolmogorov distribution, published and analytic values", "[analysis]") {
  // Marsaglia, Tsang & Wang (2003), section 4: K(10, 0.274) = 0.6284796154565043.
  CHECK(kolmogorov_cdf_exact(10, 0.274) == Approx(0.6284796154565043).epsilon(1e-12));
  // n = 1: D_1 = max(U, 1 - U), so P(D_1 < d) = 2d - 1 for 1/2 <= d <= 1.
  for (double d : {0.55, 0.7, 0.95}) CHECK(kolmogorov_cdf_exact(1, d) == Approx(2 * d - 1).epsilon(1e-12));
  // Monotone in d, bounded in [0, 1], and close to the limit law for large n.
  double prev = 0;
  for (double d = 0.01; d < 0.5; d += 0.01) {
    const double v = kolmogorov_cdf_exact(50, d);
    CHECK(v >= prev - 1e-15);
    CHECK(v <= 1.0);
    prev = v;
  }
  CHECK(kolmogorov_cdf_exact(2000, 1.0 / std::sqrt(2000.0)) ==
        Approx(kolmogorov_cdf_asymptotic(1.0)).margin(5e-3));
  // Limit law: both series forms agree around x = 1, and P(K <= 1.358) ~ 0.95 (the classic 5 % point).
  CHECK(kolmogorov_cdf_asymptotic(0.999999) == Approx(kolmogorov_cdf_asymptotic(1.000001)).epsilon(1e-5));
  CHECK(kolmogorov_cdf_asymptotic(1.3580986393225507) == Approx(0.95).epsilon(1e-9));
}

TEST_CASE("analysis: ks_test agrees with R's ks.test", "[analysis]") {
  const auto ref = read_csv(analysis_data("ref_ks.csv"));
  REQUIRE(ref.rows.size() == 7);
  const boost::math::normal_distribution<double> normal;
  for (size_t r = 0; r < ref.rows.size(); ++r) {
    std::vector<double> x;
    std::stringstream ss(ref.cell(r, ref.column("sample")));
    for (std::string item; std::getline(ss, item, ';');) x.push_back(std::stod(item));
    const int n = static_cast<int>(ref_number(ref, r, "n"));
    REQUIRE(static_cast<int>(x.size()) == n);
    INFO("n = " << n);
    auto cdf = [&](double v) { return boost::math::cdf(normal, v); };
    const auto def = ks_test(x, cdf);
    CHECK(def.statistic == Approx(ref_number(ref, r, "D")).epsilon(1e-12));
    CHECK(def.exact == (n < 100));
    CHECK(def.p == Approx(ref_number(ref, r, "p_exact_or_default")).epsilon(1e-9));
    // R's limiting series stops at an absolute tolerance of 1e-6.
    CHECK(ks_test(x, cdf, 0).p == Approx(ref_number(ref, r, "p_asymptotic")).margin(2e-6));
  }
  CHECK_THROWS_AS(ks_test({}, [](double) { return 0.5; }), InputError);
}

TEST_CASE("analysis: normality check and pair reliability", "[analysis]") {
  std::vector<double> v;
  for (int i = 1; i <= 40; ++i) v.push_back(std::sin(i * 1.7) + 0.01 * i);
  const auto nc = normality_check(v);
  REQUIRE(nc.sample.size() == 40);
  CHECK(std::is_sorted(nc.sample.begin(), nc.sample.end()));
  CHECK(nc.theoretical.front() == Approx(-nc.theoretical.back()));
  // Identical items: r = 1, alpha = 1. Independent-looking items: alpha near 0.
  const std::vector<double> a = {1, 2, 3, 4, 5, 6, 7, 3, 4, 5};
  auto same = pair_reliability(a, a);
  CHECK(same.pearson_r == Approx(1.0));
  CHECK(same.cronbach_alpha == Approx(1.0));
  // For two items alpha = 2 r' / (1 + r') when variances are equal (Spearman-Brown).
  const std::vector<double> b = {2, 1, 3, 5, 4, 7, 6, 4, 3, 5};
  const auto rel = pair_reliability(a, b);
  CHECK(rel.cronbach_alpha < 1.0);
  CHECK_THROWS_AS(pair_reliability(a, {1, 2}), InputError);
}

}  // namespace test_kolmogorov_smirnov
