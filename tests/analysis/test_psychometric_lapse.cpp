// Fitted symmetric lapse rates against R (scripts/make_reference_lapse.R: nlminb on the same likelihood,
// tests/data/analysis/ref_lapse_fits.csv), the lambda = 0 boundary, the deviance check and the CLI.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "analysis/psychometric_fit.hpp"
#include "analysis/psychometric_goodness.hpp"
#include "analysis/psychometric_lapse.hpp"
#include "framework/core/error.hpp"
#include "tests/analysis/reference_table.hpp"
#include "tests/support/run_cli.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_psychometric_lapse {

using namespace crowdlab;
using namespace crowdlab::analysis;
using crowdlab::test::analysis_data;
using crowdlab::test::close_rel;
using crowdlab::test::ref_number;
using crowdlab::test::run_cli;

namespace {
using Trials =
    std::map<std::pair<std::string, std::string>, std::pair<std::vector<double>, std::vector<double>>>;

Trials lapse_trials() {
  const auto t = read_csv(analysis_data("lapse_trials.csv"));
  Trials groups;
  for (size_t r = 0; r < t.rows.size(); ++r) {
    auto& g = groups[{t.cell(r, t.column("subject")), t.cell(r, t.column("condition"))}];
    g.first.push_back(t.number(r, t.column("distance")));
    g.second.push_back(t.number(r, t.column("collision")));
  }
  return groups;
}

PsychometricOptions symmetric() {
  PsychometricOptions o;
  o.fit_symmetric_lapse = true;
  return o;
}
}  // namespace

TEST_CASE("analysis: fitted symmetric lapse rates agree with R nlminb", "[analysis]") {
  const auto groups = lapse_trials();
  const auto ref = read_csv(analysis_data("ref_lapse_fits.csv"));
  REQUIRE(ref.rows.size() == 13);
  int at_boundary = 0, interior = 0, steps = 0;
  for (size_t r = 0; r < ref.rows.size(); ++r) {
    const auto& g = groups.at({ref.cell(r, 0), ref.cell(r, 1)});
    INFO("subject " << ref.cell(r, 0) << " condition " << ref.cell(r, 1));
    const auto fit = fit_psychometric(g.first, g.second, symmetric());
    REQUIRE(fit.converged);
    CHECK(fit.lapse_fitted);
    CHECK(fit.guess == fit.lapse);
    // The likelihood is what both optimisers minimise: it must agree tightly, and crowdlab's must not
    // be worse than R's.
    CHECK(fit.nll == Approx(ref_number(ref, r, "nll")).margin(1e-7));
    CHECK(fit.nll <= ref_number(ref, r, "nll") + 1e-9);
    CHECK(fit.lapse == Approx(ref_number(ref, r, "lambda")).margin(1e-5));
    if (fit.step_not_identified) {
      // Separation up to lapses: the likelihood rises towards a step as the slope grows, so R and
      // crowdlab stop at different slopes on that ridge; both thresholds lie in the step's interval.
      ++steps;
      const auto step = best_step(g.first, g.second);
      CHECK(fit.warning.find("not identified") != std::string::npos);
      for (double t : {fit.threshold(0.5), ref_number(ref, r, "x50")}) {
        CHECK(t > step.below);
        CHECK(t < step.above);
      }
      continue;
    }
    CHECK(fit.warning.empty());
    CHECK(close_rel(fit.intercept, ref_number(ref, r, "intercept"), 1e-5));
    CHECK(close_rel(fit.slope, ref_number(ref, r, "slope"), 1e-5));
    CHECK(close_rel(fit.threshold(0.5), ref_number(ref, r, "x50"), 1e-5));
    CHECK(close_rel(fit.threshold(0.05), ref_number(ref, r, "x05"), 1e-5));
    const auto gof = psychometric_goodness(g.first, g.second, fit, 3);
    CHECK(gof.df == static_cast<int>(ref_number(ref, r, "deviance_df")));
    CHECK(close_rel(gof.deviance, ref_number(ref, r, "deviance"), 1e-5));
    CHECK(close_rel(gof.p, ref_number(ref, r, "deviance_p"), 1e-4));
    if (ref_number(ref, r, "lambda") == 0.0) {
      ++at_boundary;
      CHECK(fit.lapse_at_boundary);
      // On the boundary the model is the plain logistic fit, exactly.
      const auto plain = fit_psychometric(g.first, g.second);
      CHECK(fit.intercept == plain.intercept);
      CHECK(fit.slope == plain.slope);
      CHECK(fit.nll == Approx(plain.nll).margin(1e-12));
    } else {
      ++interior;
      CHECK_FALSE(fit.lapse_at_boundary);
      // A fitted lambda > 0 fits better than the plain model.
      CHECK(fit.nll < fit_psychometric(g.first, g.second).nll);
    }
  }
  // The reference data exercise both cases.
  CHECK(at_boundary >= 1);
  CHECK(interior >= 3);
  CHECK(steps == 2);  // subjects 3 and 5, condition a
}

TEST_CASE("analysis: the deviance check flags a non-stationary observer", "[analysis]") {
  const auto groups = lapse_trials();
  const auto& odd = groups.at({"7", "a"});
  const auto fit = fit_psychometric(odd.first, odd.second, symmetric());
  const auto gof = psychometric_goodness(odd.first, odd.second, fit, 3);
  CHECK(gof.overdispersed);
  CHECK(gof.dispersion > 2);
  // A well-behaved observer passes, and the expected counts of the model itself give deviance ~ 0.
  const auto& ok = groups.at({"1", "a"});
  CHECK_FALSE(
      psychometric_goodness(ok.first, ok.second, fit_psychometric(ok.first, ok.second, symmetric()), 3)
          .overdispersed);
  std::vector<double> x, y;
  for (int level = 0; level <= 8; ++level) {
    const double d = 0.1 + 0.1 * level;
    const double p = 0.04 + 0.92 / (1.0 + std::exp(15.0 * (d - 0.5)));
    const int yes = static_cast<int>(std::lround(p * 2000));
    for (int t = 0; t < 2000; ++t) {
      x.push_back(d);
      y.push_back(t < yes ? 1.0 : 0.0);
    }
  }
  const auto exact = fit_psychometric(x, y, symmetric());
  CHECK(exact.lapse == Approx(0.04).margin(1e-3));
  CHECK(exact.threshold(0.5) == Approx(0.5).margin(1e-3));
  CHECK(psychometric_goodness(x, y, exact, 3).deviance < 0.1);
}

TEST_CASE("analysis: a fitted lapse excludes fixed rates, separated answers stay at lambda = 0",
          "[analysis]") {
  PsychometricOptions both = symmetric();
  both.lapse = 0.02;
  CHECK_THROWS_AS(fit_psychometric({0.1, 0.2, 0.3}, {1, 0, 1}, both), InputError);
  const auto sep = fit_psychometric({0.2, 0.3, 0.4, 0.5, 0.6}, {1, 1, 1, 0, 0}, symmetric());
  CHECK(sep.separated);
  CHECK(sep.lapse == 0.0);
  CHECK(sep.lapse_at_boundary);
  CHECK(std::isfinite(sep.nll));
}

TEST_CASE("analysis: analyze psychometric --lapse symmetric|fixed|NUMBER", "[analysis][cli]") {
  const auto csv = analysis_data("lapse_trials.csv");
  const std::vector<std::string> base = {"analyze",    "psychometric", "--csv", csv,
                                         "--subject",  "subject",      "--x",   "distance",
                                         "--response", "collision",    "--by",  "condition"};
  auto with = [&](std::vector<std::string> extra) {
    auto args = base;
    args.insert(args.end(), extra.begin(), extra.end());
    return run_cli(args);
  };
  const auto fitted = with({"--lapse", "symmetric", "--json"});
  INFO(fitted.err);
  REQUIRE(fitted.exit_code == 0);
  const auto j = nlohmann::json::parse(fitted.out);
  REQUIRE(j["fits"].size() == 13);
  for (const char* key : {"lapse", "lapse_fitted", "lapse_at_boundary", "step_not_identified", "nll",
                          "deviance", "deviance_df", "deviance_p", "dispersion", "overdispersed"})
    CHECK(j["fits"][0].contains(key));
  CHECK(j["fits"][0]["lapse_fitted"] == true);
  const auto fixed = with({"--lapse", "fixed", "--json"});
  REQUIRE(fixed.exit_code == 0);
  const auto f = nlohmann::json::parse(fixed.out);
  CHECK(f["fits"][0]["lapse"] == 0.0);
  CHECK(f["fits"][0]["lapse_at_boundary"].is_null());
  CHECK(f["fits"][0]["deviance_df"] == 7);
  const auto number = with({"--lapse", "0.05", "--json"});
  REQUIRE(number.exit_code == 0);
  CHECK(nlohmann::json::parse(number.out)["fits"][0]["lapse"] == 0.05);
  for (const char* value : {"sometimes", "nan", "-0.1", "1"}) {  // nan was a CSV problem of subject '1'
    const auto bad = with({"--lapse", value});
    CHECK(bad.exit_code == 2);
    CHECK_THAT(bad.err, Catch::StartsWith("crowdlab: error: --lapse: ") && Catch::Contains(value));
  }
  const auto clash = with({"--lapse", "symmetric", "--guess", "0.5"});
  CHECK(clash.exit_code == 2);
}

}  // namespace test_psychometric_lapse
