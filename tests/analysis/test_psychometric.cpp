// Psychometric fits against R's glm(binomial) (tests/data/analysis/ref_psychometric_glm.csv), separation,
// guess/lapse and bootstrap.
#include <catch2/catch.hpp>
#include <cmath>
#include <map>

#include "analysis/psychometric_fit.hpp"
#include "analysis/psychometric_table.hpp"
#include "framework/core/error.hpp"
#include "framework/core/seed.hpp"
#include "tests/analysis/reference_table.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_psychometric {

using namespace crowdlab;
using namespace crowdlab::analysis;
using crowdlab::test::analysis_data;
using crowdlab::test::close_rel;
using crowdlab::test::ref_number;

TEST_CASE("analysis: plain-ML psychometric thresholds agree with R glm(binomial) to 1e-6", "[analysis]") {
  const auto trials = read_csv(analysis_data("psychometric_trials.csv"));
  std::map<std::pair<std::string, std::string>, std::pair<std::vector<double>, std::vector<double>>> groups;
  for (size_t r = 0; r < trials.rows.size(); ++r) {
    auto& g = groups[{trials.cell(r, 0), trials.cell(r, 1)}];
    g.first.push_back(trials.number(r, trials.column("distance")));
    g.second.push_back(trials.number(r, trials.column("collision")));
  }
  const auto ref = read_csv(analysis_data("ref_psychometric_glm.csv"));
  REQUIRE(ref.rows.size() == 18);
  for (size_t r = 0; r < ref.rows.size(); ++r) {
    const auto& g = groups.at({ref.cell(r, 0), ref.cell(r, 1)});
    const auto fit = fit_psychometric(g.first, g.second);
    INFO("participant " << ref.cell(r, 0) << " shoulder " << ref.cell(r, 1));
    REQUIRE(fit.converged);
    CHECK_FALSE(fit.separated);
    CHECK(fit.warning.empty());
    CHECK(close_rel(fit.intercept, ref_number(ref, r, "intercept"), 1e-6));
    CHECK(close_rel(fit.slope, ref_number(ref, r, "slope"), 1e-6));
    CHECK(close_rel(fit.threshold(0.5), ref_number(ref, r, "x50"), 1e-6));
    CHECK(close_rel(fit.threshold(0.05), ref_number(ref, r, "x05"), 1e-6));
  }
}

TEST_CASE("analysis: psychometric fit recovers a known curve and is invariant to trial order", "[analysis]") {
  // Expected counts of a logistic with threshold 0.4 and slope -20 (many trials per level): the ML
  // estimate of grouped data equal to the expectations is the true curve.
  std::vector<double> x, y;
  for (int level = 0; level <= 10; ++level) {
    const double d = 0.2 + 0.04 * level;
    const double p = 1.0 / (1.0 + std::exp(20.0 * (d - 0.4)));
    const int yes = static_cast<int>(std::lround(p * 1000));
    for (int t = 0; t < 1000; ++t) {
      x.push_back(d);
      y.push_back(t < yes ? 1.0 : 0.0);
    }
  }
  const auto fit = fit_psychometric(x, y);
  CHECK(fit.threshold(0.5) == Approx(0.4).margin(2e-3));
  CHECK(fit.slope == Approx(-20).epsilon(0.02));
  std::reverse(x.begin(), x.end());
  std::reverse(y.begin(), y.end());
  const auto fit2 = fit_psychometric(x, y);
  CHECK(fit2.intercept == Approx(fit.intercept).epsilon(1e-9));
}

TEST_CASE("analysis: complete separation gives a warning and a bounded Firth estimate", "[analysis]") {
  const std::vector<double> x = {0.2, 0.25, 0.3, 0.35, 0.4, 0.45, 0.5, 0.55, 0.6, 0.65, 0.7};
  const std::vector<double> y = {1, 1, 1, 1, 1, 0, 0, 0, 0, 0, 0};
  CHECK(is_separated(x, y));
  const auto fit = fit_psychometric(x, y);
  CHECK(fit.separated);
  CHECK(fit.converged);
  CHECK(fit.warning.find("separation") != std::string::npos);
  CHECK(std::isfinite(fit.slope));
  CHECK(fit.slope < 0);
  CHECK(std::abs(fit.slope) < 1e3);
  CHECK(fit.threshold(0.5) == Approx(0.425).margin(0.03));
  // Quasi-complete (a tie at the boundary) and one-answer data are separated too.
  CHECK(is_separated({0.1, 0.2, 0.2, 0.3}, {1, 1, 0, 0}));
  CHECK(is_separated({0.1, 0.2, 0.3}, {1, 1, 1}));
  CHECK_FALSE(is_separated({0.1, 0.2, 0.3, 0.4}, {1, 0, 1, 0}));
  CHECK_THROWS_AS(fit_psychometric({0.1, 0.2}, {1, 2}), InputError);
  CHECK_THROWS_AS(fit_psychometric({0.1, 0.1}, {1, 0}), InputError);
}

TEST_CASE("analysis: guess and lapse rates and parametric bootstrap", "[analysis]") {
  std::vector<double> x, y;
  Rng rng(derive_seed(42, "psychometric-test"));
  for (int level = 0; level < 11; ++level)
    for (int t = 0; t < 60; ++t) {
      const double d = 0.2 + 0.05 * level;
      const double p = 0.1 + 0.85 / (1.0 + std::exp(-25.0 * (d - 0.45)));
      x.push_back(d);
      y.push_back(uniform01(rng) < p ? 1.0 : 0.0);
    }
  PsychometricOptions opt;
  opt.guess = 0.1;
  opt.lapse = 0.05;
  const auto fit = fit_psychometric(x, y, opt);
  REQUIRE(fit.converged);
  CHECK(fit.threshold(0.5) == Approx(0.45).margin(0.03));
  CHECK(fit.probability(fit.threshold(0.5)) == Approx(0.1 + 0.85 / 2));
  const int reps = test::kSanitized ? 20 : 200;
  const auto ci = bootstrap_thresholds(x, fit, {0.5, 0.05}, reps, 7, opt);
  REQUIRE(ci.size() == 2);
  CHECK(ci[0].lower < fit.threshold(0.5));
  CHECK(ci[0].upper > fit.threshold(0.5));
  CHECK(ci[0].replicates_used == reps);
  // Same seed, same interval.
  const auto again = bootstrap_thresholds(x, fit, {0.5, 0.05}, reps, 7, opt);
  CHECK(again[0].lower == ci[0].lower);
  CHECK(again[1].upper == ci[1].upper);
}

TEST_CASE("analysis: psychometric table with cube-root volumes, groups and bad rows", "[analysis]") {
  // Volumes v = x^3 with P(collision) rising in x: fitting with the cbrt transform equals fitting x.
  std::string text = "p,volume,yes,cond\n";
  std::vector<double> xs, ys;
  Rng rng(derive_seed(5, "volumes"));
  for (int s = 1; s <= 4; ++s)
    for (const char* cond : {"A", "B"})
      for (int level = 0; level < 9; ++level)
        for (int t = 0; t < 6; ++t) {
          const double x = 0.05 + 0.03 * level;
          const double y = uniform01(rng) < 1.0 / (1.0 + std::exp(-40.0 * (x - 0.17))) ? 1.0 : 0.0;
          text +=
              std::to_string(s) + "," + csv_number(x * x * x) + "," + (y > 0 ? "1" : "0") + "," + cond + "\n";
          if (s == 1 && std::string(cond) == "A") {
            xs.push_back(x);
            ys.push_back(y);
          }
        }
  PsychometricRequest req;
  req.subject = "p";
  req.x = "volume";
  req.response = "yes";
  req.by = "cond";
  req.x_transform = "cbrt";
  const auto a = analyze_psychometric(parse_csv(text, "v.csv"), req);
  REQUIRE(a.fits.size() == 8);
  REQUIRE(a.groups.size() == 2);
  CHECK(a.groups[0].n == 4);
  const auto direct = fit_psychometric(xs, ys);
  CHECK(a.fits[0].fit.slope > 0);
  CHECK(a.fits[0].thresholds[0] == Approx(direct.threshold(0.5)).epsilon(1e-9));
  REQUIRE(a.threshold_anova.has_value());
  CHECK(a.threshold_anova->effects[0].name == "cond");
  CHECK(a.threshold_anova->effects[0].df1 == 1);
  const auto json = psychometric_to_json(a);
  CHECK(json["fits"][0]["thresholds"].contains("0.5"));
  CHECK(json["groups"][1]["by"] == "B");
  try {
    analyze_psychometric(parse_csv("p,volume,yes,cond\n1,-0.5,1,A\n", "neg.csv"), req);
    FAIL("expected InputError");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("neg.csv:2") != std::string::npos);
  }
}

}  // namespace test_psychometric
