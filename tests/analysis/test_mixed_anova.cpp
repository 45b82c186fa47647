// Mixed (split-plot) and between-subjects ANOVA against R afex::aov_ez(type = 3) / car::Anova
// (scripts/make_reference_mixed_anova.R, tests/data/analysis/ref_mixed_*.csv, ref_between_*.csv), with
// unequal group sizes, and bad input.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>

#include "analysis/rm_anova.hpp"
#include "framework/core/error.hpp"
#include "tests/analysis/reference_table.hpp"
#include "tests/support/run_cli.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_mixed_anova {

using namespace crowdlab;
using namespace crowdlab::analysis;
using crowdlab::test::analysis_data;
using crowdlab::test::close_rel;
using crowdlab::test::ref_number;
using crowdlab::test::run_cli;

namespace {
struct Case {
  std::string data, reference, subject, dv;
  std::vector<std::string> within, between;
};
const std::vector<Case> kCases = {
    // O'Brien & Kaiser (1985) from afex: 3 x 2 between with cells of 2 to 4 subjects, 3 x 5 within.
    {"obk_long", "ref_mixed_obk_long", "id", "value", {"phase", "hour"}, {"treatment", "gender"}},
    // Simulated: lab (7) and online (11) groups, 3 x 2 within, 2 repetitions per cell.
    {"mixed_sim", "ref_mixed_mixed_sim", "id", "score", {"density", "method"}, {"group"}},
    // Between-subjects only, on each subject's mean.
    {"obk_long", "ref_between_obk_long", "id", "value", {}, {"treatment", "gender"}},
};

}  // namespace

TEST_CASE("analysis: mixed and between ANOVAs agree with afex type 3 to 1e-6, effects in afex's order",
          "[analysis]") {
  for (const auto& c : kCases) {
    const auto design = build_within_design(read_csv(analysis_data(c.data + ".csv")), c.dv, c.subject,
                                            c.within, {}, c.between);
    const auto res = rm_anova(design);
    const auto ref = read_csv(analysis_data(c.reference + ".csv"));
    REQUIRE(res.effects.size() == ref.rows.size());
    for (size_t r = 0; r < ref.rows.size(); ++r) {
      const auto& e = res.effects[r];
      INFO(c.reference << " effect " << ref.cell(r, 0));
      CHECK(e.name == ref.cell(r, ref.column("effect")));
      CHECK(e.df1 == ref_number(ref, r, "df1"));
      CHECK(e.df2 == ref_number(ref, r, "df2"));
      CHECK(close_rel(e.ss, ref_number(ref, r, "SS"), 1e-9));
      CHECK(close_rel(e.ss_error, ref_number(ref, r, "SS_error"), 1e-9));
      CHECK(close_rel(e.f, ref_number(ref, r, "F"), 1e-6));
      CHECK(close_rel(e.p, ref_number(ref, r, "p"), 1e-6));
      CHECK(close_rel(e.pes, ref_number(ref, r, "pes"), 1e-6));
      CHECK(close_rel(e.ges, ref_number(ref, r, "ges"), 1e-6));
      CHECK(crowdlab::test::optional_matches(e.mauchly_w, ref_number(ref, r, "mauchly_W")));
      CHECK(crowdlab::test::optional_matches(e.mauchly_p, ref_number(ref, r, "mauchly_p")));
      CHECK(crowdlab::test::optional_matches(e.gg_eps, ref_number(ref, r, "gg_eps")));
      CHECK(crowdlab::test::optional_matches(e.hf_eps, ref_number(ref, r, "hf_eps")));
      CHECK(crowdlab::test::optional_matches(e.p_gg, ref_number(ref, r, "p_gg")));
      CHECK(crowdlab::test::optional_matches(e.p_hf, ref_number(ref, r, "p_hf")));
    }
  }
}

TEST_CASE("analysis: mixed ANOVA results do not depend on row or level order", "[analysis]") {
  auto table = read_csv(analysis_data("mixed_sim.csv"));
  const auto a = rm_anova(build_within_design(table, "score", "id", {"density", "method"}, {}, {"group"}));
  std::reverse(table.rows.begin(), table.rows.end());
  std::reverse(table.line_numbers.begin(), table.line_numbers.end());
  const auto b = rm_anova(build_within_design(table, "score", "id", {"density", "method"}, {}, {"group"}));
  REQUIRE(a.effects.size() == b.effects.size());
  for (size_t i = 0; i < a.effects.size(); ++i) {
    CHECK(a.effects[i].name == b.effects[i].name);
    CHECK(a.effects[i].f == Approx(b.effects[i].f).epsilon(1e-10));
  }
}

TEST_CASE("analysis: analyze anova --between: JSON keys, nulls and bad input (exit 2)", "[analysis][cli]") {
  const auto r = run_cli({"analyze", "anova", "--csv", analysis_data("mixed_sim.csv"), "--dv", "score",
                          "--subject", "id", "--within", "density,method", "--between", "group", "--json"});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const auto j = nlohmann::json::parse(r.out);
  REQUIRE(j["effects"].size() == 7);
  CHECK(j["effects"][0]["effect"] == "group");
  CHECK(j["effects"][2]["effect"] == "group:density");
  for (const char* key : {"effect", "df1", "df2", "F", "p", "pes", "gg_eps", "p_gg", "hf_eps", "p_hf",
                          "mauchly_W", "mauchly_p"})
    for (const auto& e : j["effects"]) CHECK(e.contains(key));
  CHECK(j["effects"][0]["gg_eps"].is_null());     // between effect
  CHECK(j["effects"][3]["mauchly_W"].is_null());  // method: df1 = 1
  CHECK(j["effects"][2]["gg_eps"].is_number());   // group:density gets density's correction
  const auto between_only = run_cli({"analyze", "anova", "--csv", analysis_data("obk_long.csv"), "--dv",
                                     "value", "--subject", "id", "--between", "treatment,gender"});
  INFO(between_only.err);
  CHECK(between_only.exit_code == 0);
  CHECK(between_only.out.find("Between-subjects ANOVA") != std::string::npos);

  const auto dir = test::scratch_dir("analyze_mixed_bad");
  auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream((dir / name).string()) << text;
    return (dir / name).string();
  };
  auto anova = [&](const std::string& csv, const std::string& within, const std::string& between) {
    std::vector<std::string> args = {"analyze", "anova", "--csv", csv, "--dv", "y", "--subject", "s"};
    if (!within.empty()) args.insert(args.end(), {"--within", within});
    if (!between.empty()) args.insert(args.end(), {"--between", between});
    return run_cli(args);
  };
  // Six subjects in G x H with one combination empty.
  std::string rows = "s,G,H,A,y\n";
  const char* groups[] = {"g1,h1", "g1,h1", "g1,h2", "g2,h1", "g2,h1", "g1,h2"};
  for (int s = 0; s < 6; ++s)
    for (const char* a : {"a1", "a2"})
      rows += std::to_string(s) + "," + groups[s] + "," + a + "," +
              std::to_string(s * 1.5 + (a[1] - '0') * s % 3) + "\n";
  const auto empty_group = anova(write("empty.csv", rows), "A", "G,H");
  CHECK(empty_group.exit_code == 2);
  CHECK(empty_group.err.find("no subject") != std::string::npos);
  const auto switching =
      anova(write("switch.csv", "s,G,A,y\n1,g1,a1,1\n1,g2,a2,2\n2,g1,a1,3\n2,g1,a2,1\n"), "A", "G");
  CHECK(switching.exit_code == 2);
  CHECK(switching.err.find("switch.csv:3") != std::string::npos);
  CHECK(switching.err.find("two levels") != std::string::npos);
  const auto one_subject = anova(write("one.csv", "s,G,A,y\n1,g1,a1,1\n1,g1,a2,2\n"), "A", "G");
  CHECK(one_subject.exit_code == 2);
  const auto one_per_group =
      anova(write("few.csv", "s,G,A,y\n1,g1,a1,1\n1,g1,a2,2\n2,g2,a1,3\n2,g2,a2,1\n3,g2,a1,2\n3,g2,a2,5\n"),
            "A", "G");
  CHECK(one_per_group.exit_code == 2);
  CHECK(one_per_group.err.find("residual degrees of freedom") != std::string::npos);
  std::string constant = "s,G,A,y\n";
  for (int s = 0; s < 6; ++s)
    constant += std::to_string(s) + "," + (s % 2 ? "g1" : "g2") + ",a1,4\n" + std::to_string(s) + "," +
                (s % 2 ? "g1" : "g2") + ",a2,4\n";
  const auto flat = anova(write("constant.csv", constant), "A", "G");
  CHECK(flat.exit_code == 2);
  CHECK(flat.err.find("constant") != std::string::npos);
  const auto nan =
      anova(write("nan.csv", "s,G,A,y\n1,g1,a1,NaN\n1,g1,a2,2\n2,g2,a1,3\n2,g2,a2,1\n"), "A", "G");
  CHECK(nan.exit_code == 2);
  CHECK(nan.err.find("nan.csv:2") != std::string::npos);
  const auto same = anova(write("same.csv", "s,G,A,y\n1,g1,a1,1\n"), "G", "G");
  CHECK(same.exit_code == 2);
  CHECK(same.err.find("named twice") != std::string::npos);
}

}  // namespace test_mixed_anova
