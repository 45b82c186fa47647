// emmeans-style post-hocs (--error pooled|separate) against R emmeans after afex::aov_ez on md_12.1
// (scripts/make_reference_emmeans.R, tests/data/analysis/ref_emmeans_md_12.1.csv): 1e-6 relative.
#include <algorithm>
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "analysis/posthoc.hpp"
#include "framework/core/error.hpp"
#include "tests/analysis/reference_table.hpp"
#include "tests/support/run_cli.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_posthoc_error {

using namespace crowdlab;
using namespace crowdlab::analysis;
using crowdlab::test::analysis_data;
using crowdlab::test::close_rel;
using crowdlab::test::ref_number;

namespace {
// Checks a post-hoc family against the emmeans rows of (model, effect, adjust) in `ref`; returns how many
// were compared.
size_t check_against_emmeans(const PosthocResult& res, const CsvTable& ref, const std::string& model,
                             const std::string& effect, const std::string& adjust) {
  size_t checked = 0;
  for (size_t r = 0; r < ref.rows.size(); ++r) {
    if (ref.cell(r, 0) != model || ref.cell(r, 1) != effect || ref.cell(r, 2) != adjust) continue;
    const auto& label = ref.cell(r, ref.column("contrast"));
    const auto bar = label.find('|');
    // emmeans orders cells with the first factor fastest, crowdlab with it slowest: a pair may be
    // reversed (estimate and t change sign).
    const std::string first = label.substr(0, bar), second = label.substr(bar + 1);
    const auto it = std::find_if(res.pairs.begin(), res.pairs.end(), [&](const auto& p) {
      return (p.level_a == first && p.level_b == second) || (p.level_a == second && p.level_b == first);
    });
    INFO(model << " " << effect << " " << adjust << " " << label);
    REQUIRE(it != res.pairs.end());
    ++checked;
    const double sign = it->level_a == first ? 1.0 : -1.0;
    CHECK(close_rel(sign * it->difference, ref_number(ref, r, "estimate"), 1e-9));
    CHECK(close_rel(it->se, ref_number(ref, r, "se"), 1e-6));
    CHECK(close_rel(it->df, ref_number(ref, r, "df"), 1e-6));
    CHECK(close_rel(sign * it->statistic, ref_number(ref, r, "t"), 1e-6));
    CHECK(close_rel(it->p, ref_number(ref, r, "p"), 1e-6));
    // emmeans' Tukey p comes from R's ptukey, which loses accuracy for small df and in the far tail
    // (docs/analysis.md: up to 17 % at df = 2; crowdlab's matches the defining integral to 1e-10):
    // 1e-6 absolute there, Bonferroni 1e-6 relative.
    if (adjust == "tukey")
      CHECK(it->p_adjusted == Approx(ref_number(ref, r, "p_adjusted")).margin(1e-6));
    else
      CHECK(close_rel(it->p_adjusted, ref_number(ref, r, "p_adjusted"), 1e-6));
  }
  return checked;
}
}  // namespace

TEST_CASE("analysis: posthoc --error pooled|separate agree with emmeans (univariate|multivariate)",
          "[analysis]") {
  const auto design =
      build_within_design(read_csv(analysis_data("md_12.1.csv")), "rt", "id", {"angle", "noise"});
  const auto ref = read_csv(analysis_data("ref_emmeans_md_12.1.csv"));
  size_t checked = 0;
  for (const char* model : {"univariate", "multivariate"})
    for (const char* effect : {"angle", "angle:noise"})
      for (const char* adjust : {"tukey", "bonferroni"}) {
        const auto error = std::string(model) == "univariate" ? PosthocError::pooled : PosthocError::separate;
        const auto method = std::string(adjust) == "tukey" ? PosthocMethod::tukey : PosthocMethod::bonferroni;
        const auto res = posthoc(design, parse_effect(design, effect), method, false, 1000, error);
        checked += check_against_emmeans(res, ref, model, effect, adjust);
      }
  CHECK(checked == 72);
}

// Issue 20: a between factor (lab 7 vs online 11 subjects) with two within factors; between, within and
// mixed cells, unequal groups (emmeans' equal weights), Satterthwaite across the subject stratum.
TEST_CASE("analysis: posthoc --between agrees with emmeans on a mixed design (both models)", "[analysis]") {
  const auto design = build_within_design(read_csv(analysis_data("mixed_sim.csv")), "score", "id",
                                          {"density", "method"}, {}, {"group"});
  const auto ref = read_csv(analysis_data("ref_emmeans_mixed_sim.csv"));
  size_t checked = 0;
  for (const char* model : {"univariate", "multivariate"})
    for (const char* effect : {"group", "density", "group:density", "group:method", "group:density:method"})
      for (const char* adjust : {"tukey", "bonferroni"}) {
        const auto error = std::string(model) == "univariate" ? PosthocError::pooled : PosthocError::separate;
        const auto method = std::string(adjust) == "tukey" ? PosthocMethod::tukey : PosthocMethod::bonferroni;
        const auto res =
            posthoc_mixed(design, parse_mixed_effect(design, effect), method, false, 1000, error);
        checked += check_against_emmeans(res, ref, model, effect, adjust);
      }
  CHECK(checked == ref.rows.size());
  CHECK(checked == 364);
  CHECK_THROWS_AS(posthoc_mixed(design, parse_mixed_effect(design, "group"), PosthocMethod::tukey, false,
                                1000, PosthocError::classic),
                  InputError);
}

TEST_CASE("analysis: analyze posthoc --error keeps the classic default and labels cells a:b",
          "[analysis][cli]") {
  const std::vector<std::string> base = {"analyze",  "posthoc",     "--csv",     analysis_data("md_12.1.csv"),
                                         "--dv",     "rt",          "--subject", "id",
                                         "--within", "angle,noise", "--effect",  "angle:noise",
                                         "--json"};
  auto args = base;
  args.insert(args.end(), {"--error", "pooled"});
  const auto pooled = crowdlab::test::run_cli(args);
  INFO(pooled.err);
  REQUIRE(pooled.exit_code == 0);
  const auto j = nlohmann::json::parse(pooled.out);
  CHECK(j["error"] == "pooled");
  // Cells are labelled a:b; 0:absent vs 4:absent pools three strata (Satterthwaite df as emmeans).
  CHECK(j["comparisons"][1]["a"] == "0:absent");
  CHECK(j["comparisons"][1]["b"] == "4:absent");
  CHECK(j["comparisons"][1]["df"].get<double>() == Approx(28.604428212736856).epsilon(1e-9));
  const auto classic = crowdlab::test::run_cli(base);
  REQUIRE(classic.exit_code == 0);
  CHECK_FALSE(nlohmann::json::parse(classic.out).contains("error"));
  args = base;
  args.insert(args.end(), {"--error", "both"});
  CHECK(crowdlab::test::run_cli(args).exit_code != 0);
}

TEST_CASE("analysis: analyze posthoc --between labels cells between-first and refuses classic (exit 2)",
          "[analysis][cli]") {
  const std::vector<std::string> base = {
      "analyze",  "posthoc",        "--csv",     analysis_data("mixed_sim.csv"),
      "--dv",     "score",          "--subject", "id",
      "--within", "density,method", "--between", "group",
      "--effect", "group:density",  "--json"};
  auto args = base;
  args.insert(args.end(), {"--error", "separate"});
  const auto r = crowdlab::test::run_cli(args);
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const auto j = nlohmann::json::parse(r.out);
  CHECK(j["effect"] == "group:density");
  CHECK(j["levels"][0] == "lab:low");
  CHECK(j["comparisons"].size() == 15);
  CHECK(j["comparisons"][0]["df"].get<double>() == 16.0);  // 18 subjects - 2 groups
  const auto classic = crowdlab::test::run_cli(base);
  CHECK(classic.exit_code == 2);
  CHECK(classic.err.find("--error separate") != std::string::npos);
  args = base;
  args[args.size() - 2] = "group:colour";
  args.insert(args.end(), {"--error", "pooled"});
  const auto unknown = crowdlab::test::run_cli(args);
  CHECK(unknown.exit_code == 2);
  CHECK(unknown.err.find("colour") != std::string::npos);
}

}  // namespace test_posthoc_error
