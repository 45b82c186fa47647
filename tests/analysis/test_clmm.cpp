// Cumulative link mixed models against ordinal::clmm (scripts/make_reference_clmm.R, one random term
// and crossed participant and stimulus terms,
// tests/data/analysis/ref_clmm.csv): thresholds, fixed effects and the random SD to 1e-4, the Laplace
// log-likelihood to 1e-6 absolute; standard errors to 2e-5 against the Hessian of the exact Laplace
// log-likelihood computed in R (`laplace_se`), and to 5e-3 against clmm's printed SEs, whose
// finite-difference Hessian carries up to 0.3 % of numerical noise here (docs/analysis.md); bad input.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "analysis/clmm_fit.hpp"
#include "analysis/model_not_fitted.hpp"
#include "framework/core/error.hpp"
#include "tests/analysis/reference_table.hpp"
#include "tests/support/run_cli.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_clmm {

using namespace crowdlab;
using namespace crowdlab::analysis;
using crowdlab::test::analysis_data;
using crowdlab::test::run_cli;

TEST_CASE("analysis: clmm agrees with ordinal::clmm (logit, probit, a factor column, crossed intercepts)",
          "[analysis]") {
  const auto t = read_csv(analysis_data("ref_clmm.csv"));
  std::map<std::tuple<std::string, std::string, std::string>, double> ref;
  for (size_t r = 0; r < t.rows.size(); ++r) ref[{t.cell(r, 0), t.cell(r, 1), t.cell(r, 2)}] = t.number(r, 3);
  struct Model {
    std::string name, link, formula;
    std::set<std::string> categorical;
    size_t fixed;
    std::string data = "likert_sim.csv";
  };
  // "categorical": the numeric column rep as a factor, as R's factor(rep) and `analyze report`.
  const std::vector<Model> models = {
      {"logit", "logit", "rating ~ method * density + (1 | participant)", {}, 5},
      {"probit", "probit", "rating ~ method + density + (1 | participant)", {}, 3},
      {"categorical", "logit", "rating ~ method + rep + (1 | participant)", {"rep"}, 3},
      // Crossed random intercepts: 30 participants x 12 stimuli (the joint Laplace approximation).
      {"crossed",
       "logit",
       "rating ~ method + (1 | participant) + (1 | stimulus)",
       {},
       1,
       "likert_crossed.csv"}};
  for (const auto& [name, link, formula, categorical, fixed_terms, file] : models) {
    INFO(name << ": " << formula);
    const auto fit = fit_clmm(read_csv(analysis_data(file)), formula, link, categorical);
    CHECK(fit.converged);
    CHECK(fit.loglik == Approx(ref.at({name, "loglik", ""})).margin(1e-6));
    REQUIRE(fit.random.size() == (name == "crossed" ? 2u : 1u));
    for (const auto& g : fit.random) {
      INFO(g.group);
      CHECK(g.sd == Approx(ref.at({name, "sd", g.group})).epsilon(1e-4));
    }
    REQUIRE(fit.thresholds.size() == 4);
    for (const auto& c : fit.thresholds) {
      INFO(c.name);
      CHECK(c.estimate == Approx(ref.at({name, "threshold", c.name})).epsilon(1e-4).margin(1e-5));
      CHECK(c.se == Approx(ref.at({name, "laplace_threshold_se", c.name})).epsilon(2e-5));
      CHECK(c.se == Approx(ref.at({name, "threshold_se", c.name})).epsilon(5e-3));
    }
    size_t fixed = 0;
    for (const auto& c : fit.fixed) {
      INFO(c.name);
      REQUIRE(ref.count({name, "estimate", c.name}));
      ++fixed;
      CHECK(c.estimate == Approx(ref.at({name, "estimate", c.name})).epsilon(1e-4).margin(1e-5));
      CHECK(c.se == Approx(ref.at({name, "laplace_se", c.name})).epsilon(2e-5));
      CHECK(c.se == Approx(ref.at({name, "se", c.name})).epsilon(5e-3));
    }
    CHECK(fixed == fixed_terms);
  }
}

// clmm_separated.csv: one Likert item of `reproduce gomez2024 --quick`'s simulated study (8 observers x
// 40 conditions, 6 answer levels used), density prefixed with "d" so that it is a factor. R 4.2.2,
// ordinal 2022.11.16: clmm(factor(value) ~ density * viewpoint * method + (1 | participant)) stops with
// logLik -272.377147539 and "Hessian is numerically singular: parameters are not uniquely determined"
// (cells whose answers all lie at one end: coefficients run to infinity); with main effects only,
// logLik -287.920650448 and the values below.
TEST_CASE("analysis: clmm of separated data reaches R's log-likelihood and is not fitted, main effects agree",
          "[analysis]") {
  const auto t = read_csv(analysis_data("clmm_separated.csv"));
  // BOBYQA stopped at its 200000 evaluations here (about 100 s) at logLik -272.562, 0.185 below R's,
  // and reported arbitrary estimates near -11 with SEs of 300; L-BFGS on the analytic gradient walks the
  // flat directions out in a fraction of a second, where the information is singular, as R says.
  try {
    (void)fit_clmm(t, "value ~ density * viewpoint * method + (1 | participant)");
    FAIL("a separated model was fitted");
  } catch (const analysis::ModelNotFitted& e) {
    CHECK_THAT(e.what(), Catch::Contains("separated"));
  }
  const auto fit = fit_clmm(t, "value ~ density + viewpoint + method + (1 | participant)");
  CHECK(fit.converged);
  CHECK(fit.loglik >= -287.920650448 - 1e-6);  // at R's optimum or closer (R stops at gradTol 1e-4)
  CHECK(fit.loglik == Approx(-287.920650448).margin(1e-4));
  REQUIRE(fit.random.size() == 1);
  CHECK(fit.random[0].sd == Approx(0.575175173).epsilon(1e-4));
  const std::map<std::string, std::pair<double, double>> r = {
      {"1|2", {0.8877571832, 0.41884884}},           {"2|3", {2.8299248227, 0.57754833}},
      {"3|4", {4.8447829926, 0.87715362}},           {"4|5", {6.6355546489, 0.92089754}},
      {"5|6", {8.2528484061, 0.93483284}},           {"densityd3.33", {-0.5400612025, 0.37864417}},
      {"densityd4.44", {-0.4286210615, 0.36880256}}, {"densityd5.55", {-0.8605054204, 0.38248440}},
      {"densityd6.66", {-0.7049672424, 0.37966157}}, {"viewpointV2", {-0.3696221915, 0.34037563}},
      {"viewpointV3", {-0.3888445697, 0.33858349}},  {"viewpointV4", {-0.2169209612, 0.33922067}},
      {"methodours", {8.4789933860, 0.86766998}}};
  auto check = [&](const ClmmCoefficient& c) {
    INFO(c.name);
    REQUIRE(r.count(c.name));
    CHECK(c.estimate == Approx(r.at(c.name).first).epsilon(1e-4).margin(5e-5));
    CHECK(c.se == Approx(r.at(c.name).second).epsilon(5e-3));
  };
  for (const auto& c : fit.thresholds) check(c);
  for (const auto& c : fit.fixed) check(c);
  CHECK(fit.thresholds.size() + fit.fixed.size() == r.size());
}

TEST_CASE("analysis: analyze clmm --json and bad input (exit 2)", "[analysis][cli]") {
  const auto r = run_cli({"analyze", "clmm", "--csv", analysis_data("likert_sim.csv"), "--formula",
                          "rating ~ method + (1 | participant)", "--link", "probit", "--json"});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const auto j = nlohmann::json::parse(r.out);
  CHECK(j["thresholds"][0]["name"] == "1|2");
  for (const char* key : {"term", "estimate", "se", "z", "p"}) CHECK(j["fixed"][0].contains(key));
  CHECK(j["random"][0]["group"] == "participant");
  CHECK(j.contains("loglik"));
  const auto dir = test::scratch_dir("analyze_clmm_bad");
  auto clmm = [&](const std::string& file, const std::string& text, const std::string& formula) {
    std::ofstream((dir / file).string()) << text;
    return run_cli({"analyze", "clmm", "--csv", (dir / file).string(), "--formula", formula});
  };
  const auto two = clmm("two.csv", "s,a,r\n1,x,1\n1,z,2\n2,x,2\n2,z,1\n", "r ~ a + (1 | s)");
  CHECK(two.exit_code == 2);
  CHECK(two.err.find("at least 3") != std::string::npos);
  const auto slope = clmm("slope.csv", "s,a,r\n1,x,1\n1,z,2\n2,x,3\n2,z,1\n", "r ~ a + (1 + a | s)");
  CHECK(slope.exit_code == 2);
  const auto twice = clmm("twice.csv", "s,a,r\n1,x,1\n1,z,2\n2,x,3\n2,z,1\n", "r ~ a + (1 | s) + (1 | s)");
  CHECK(twice.exit_code == 2);
  CHECK(twice.err.find("two random-intercept terms") != std::string::npos);
  const auto none = clmm("none.csv", "s,a,r\n1,x,1\n1,z,2\n2,x,3\n2,z,1\n", "r ~ a");
  CHECK(none.exit_code == 2);
  const auto nan = clmm("nan.csv", "s,a,r\n1,x,1\n1,,2\n2,x,3\n2,z,1\n", "r ~ a + (1 | s)");
  CHECK(nan.exit_code == 2);
  CHECK(nan.err.find("nan.csv:3") != std::string::npos);
}

}  // namespace test_clmm
