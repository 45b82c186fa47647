// Linear mixed models against lme4::lmer (scripts/make_reference_lmm.R, tests/data/analysis/ref_lmm.csv):
// fixed effects and SEs to 1e-5, variance components to 1e-4, the criterion to 1e-6, lmerTest's
// Satterthwaite df to 1e-5 and p to 1e-4; R's term names; the singular fit; bad input.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "analysis/lmm_fit.hpp"
#include "analysis/lmm_formula.hpp"
#include "analysis/model_matrix.hpp"
#include "framework/core/error.hpp"
#include "tests/analysis/reference_table.hpp"
#include "tests/support/run_cli.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_lmm {

using namespace crowdlab;
using namespace crowdlab::analysis;
using crowdlab::test::analysis_data;
using crowdlab::test::close_rel;
using crowdlab::test::run_cli;

namespace {
// (model, quantity, name) -> value
std::map<std::tuple<std::string, std::string, std::string>, double> lmm_reference() {
  const auto t = read_csv(analysis_data("ref_lmm.csv"));
  std::map<std::tuple<std::string, std::string, std::string>, double> out;
  for (size_t r = 0; r < t.rows.size(); ++r) out[{t.cell(r, 0), t.cell(r, 1), t.cell(r, 2)}] = t.number(r, 3);
  return out;
}
}  // namespace

TEST_CASE("analysis: lmm agrees with lme4::lmer (REML, ML, random slopes, crossed, singular)", "[analysis]") {
  const auto ref = lmm_reference();
  const auto models = read_csv(analysis_data("ref_lmm_models.csv"));
  REQUIRE(models.rows.size() == 5);
  for (size_t m = 0; m < models.rows.size(); ++m) {
    const std::string name = models.cell(m, 0);
    const bool reml = models.cell(m, 3) == "TRUE";
    INFO(name << ": " << models.cell(m, 2));
    const auto fit = fit_lmm(read_csv(analysis_data(models.cell(m, 1))), models.cell(m, 2), reml);
    CHECK(fit.converged);
    const bool singular = ref.at({name, "singular", ""}) == 1.0;
    CHECK(fit.singular == singular);
    CHECK(fit.criterion == Approx(ref.at({name, "criterion", reml ? "REML" : "deviance"})).margin(1e-6));
    size_t fixed_refs = 0;
    for (const auto& f : fit.fixed) {
      INFO(f.term);
      REQUIRE(ref.count({name, "estimate", f.term}));
      ++fixed_refs;
      CHECK(close_rel(f.estimate, ref.at({name, "estimate", f.term}), 1e-5));
      CHECK(close_rel(f.se, ref.at({name, "se", f.term}), 1e-5));
      CHECK(close_rel(f.t, ref.at({name, "t", f.term}), 1e-5));
      // lmerTest's Satterthwaite df (both numerical derivatives agree to ~2e-6) and p (a df error
      // moves p ~50x more at p ~ 1e-19).
      CHECK(close_rel(f.df, ref.at({name, "df", f.term}), 1e-5));
      CHECK(close_rel(f.p, ref.at({name, "p", f.term}), 1e-4));
    }
    size_t want_fixed = 0;
    for (const auto& [key, v] : ref)
      if (std::get<0>(key) == name && std::get<1>(key) == "estimate") ++want_fixed;
    CHECK(fixed_refs == want_fixed);
    // On the boundary the variance parameters are on a flat ridge (lme4 and crowdlab stop at slightly
    // different points of it): looser there.
    const double vc_tol = singular ? 2e-3 : 1e-4;
    CHECK(close_rel(fit.residual_sd, ref.at({name, "residual_sd", ""}), vc_tol));
    for (const auto& s : fit.random_sd) {
      INFO(s.group << "/" << s.term);
      CHECK(close_rel(s.sd, ref.at({name, "sd", s.group + "/" + s.term}), vc_tol));
    }
    for (const auto& c : fit.random_corr)
      CHECK(c.corr == Approx(ref.at({name, "corr", c.group + "/" + c.term1 + "/" + c.term2})).margin(vc_tol));
  }
}

TEST_CASE("analysis: lmm formula syntax and R's term order", "[analysis]") {
  const auto f = parse_lmm_formula("y ~ a * b + c + (1 + b | S) + (1 | item)");
  CHECK(f.response == "y");
  REQUIRE(f.fixed.size() == 4);
  CHECK(f.fixed[2] == ModelTerm{"c"});
  CHECK(f.fixed[3] == ModelTerm{"a", "b"});
  REQUIRE(f.random.size() == 2);
  CHECK(f.random[0].group == "S");
  CHECK(f.random[0].intercept);
  CHECK(f.random[1].terms.empty());
  CHECK_FALSE(parse_lmm_formula("y ~ 0 + a + (0 + a | S)").random[0].intercept);
  CHECK_THROWS_AS(parse_lmm_formula("y ~ a + (a || S)"), InputError);
  CHECK_THROWS_AS(parse_lmm_formula("y ~ log(a) + (1 | S)"), InputError);
  CHECK_THROWS_AS(parse_lmm_formula("y ~ a"), InputError);
  CHECK_THROWS_AS(parse_lmm_formula("y a + (1 | S)"), InputError);
}

TEST_CASE("analysis: analyze lmm --json and bad input (exit 2)", "[analysis][cli]") {
  const auto r = run_cli({"analyze", "lmm", "--csv", analysis_data("lmm_sim.csv"), "--formula",
                          "score ~ dens_c * method + (1 + method | participant)", "--json"});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const auto j = nlohmann::json::parse(r.out);
  REQUIRE(j["fixed"].size() == 4);
  CHECK(j["fixed"][3]["term"] == "dens_c:methodours");
  for (const char* key : {"term", "estimate", "se", "t", "df", "p"}) CHECK(j["fixed"][0].contains(key));
  REQUIRE(j["random"].size() == 3);
  CHECK(j["random"][2]["term2"] == "methodours");
  CHECK(j.contains("reml_criterion"));
  CHECK(j["converged"] == true);
  const auto ml = run_cli({"analyze", "lmm", "--csv", analysis_data("lmm_sim.csv"), "--formula",
                           "score ~ method + (1 | participant)", "--ml", "--json"});
  REQUIRE(ml.exit_code == 0);
  CHECK(nlohmann::json::parse(ml.out).contains("deviance"));

  const auto dir = test::scratch_dir("analyze_lmm_bad");
  auto lmm = [&](const std::string& file, const std::string& text, const std::string& formula) {
    std::ofstream((dir / file).string()) << text;
    return run_cli({"analyze", "lmm", "--csv", (dir / file).string(), "--formula", formula});
  };
  const auto nan = lmm("nan.csv", "s,a,y\n1,x,1\n1,z,NaN\n2,x,3\n2,z,1\n3,x,2\n3,z,2\n", "y ~ a + (1 | s)");
  CHECK(nan.exit_code == 2);
  CHECK(nan.err.find("nan.csv:3") != std::string::npos);
  const auto constant =
      lmm("flat.csv", "s,a,y\n1,x,1\n1,z,1\n2,x,1\n2,z,1\n3,x,1\n3,z,1\n", "y ~ a + (1 | s)");
  CHECK(constant.exit_code == 2);
  CHECK(constant.err.find("constant") != std::string::npos);
  const auto one = lmm("one.csv", "s,a,y\n1,x,1\n1,z,2\n1,x,3\n1,z,1\n", "y ~ a + (1 | s)");
  CHECK(one.exit_code == 2);
  CHECK(one.err.find("single level") != std::string::npos);
  const auto missing_cell = lmm("cell.csv", "s,a,b,y\n1,x,u,1\n1,z,u,2\n2,x,v,3\n2,z,u,1\n3,x,u,2\n3,z,u,5\n",
                                "y ~ a * b + (1 | s)");
  CHECK(missing_cell.exit_code == 2);
  CHECK(missing_cell.err.find("rank deficient") != std::string::npos);
  const auto no_column = lmm("col.csv", "s,a,y\n1,x,1\n", "y ~ b + (1 | s)");
  CHECK(no_column.exit_code == 2);
  CHECK(no_column.err.find("'b'") != std::string::npos);
}

TEST_CASE("analysis: lmm crossings and model matrices too large are refused from the counts", "[analysis]") {
  // Issue 32: `v0*v1*...*v23` (2^24 - 1 terms) and `method` crossed 30 times ran out of memory.
  std::string crossed = "y ~ v0";
  for (int i = 1; i < 24; ++i) crossed += "*v" + std::to_string(i);
  CHECK_THROWS_WITH(parse_lmm_formula(crossed + " + (1 | S)"),
                    Catch::Contains("crossing 24 variables") && Catch::Contains("limit of 1023"));
  std::string same = "y ~ method";
  for (int i = 1; i < 30; ++i) same += "*method";
  const LmmFormula f = parse_lmm_formula(same + " + (1 | S)");  // a*a is a, as in R
  REQUIRE(f.fixed.size() == 1);
  CHECK(f.fixed[0] == ModelTerm{"method"});
  // An interaction of two 100-level factors: 9,999 columns of the design matrix, refused before the
  // rows x columns matrix is allocated.
  std::map<std::string, ModelVariable> vars;
  for (const char* name : {"a", "b"}) {
    ModelVariable v;
    v.numeric = false;
    for (int l = 0; l < 100; ++l) v.levels.push_back("L" + std::to_string(l));
    v.codes.assign(4, 0);
    vars[name] = v;
  }
  CHECK_THROWS_WITH(model_matrix({{"a"}, {"b"}, {"a", "b"}}, true, vars, 4),
                    Catch::Contains("10000 design-matrix columns") && Catch::Contains("limit of 2000"));
}

}  // namespace test_lmm
