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
#include "framework/core/error.hpp"
#include "tests/analysis/reference_table.hpp"
#include "tests/support/run_cli.hpp"

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
