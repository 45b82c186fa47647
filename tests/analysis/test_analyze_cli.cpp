// `crowdlab analyze ...` end to end: JSON shapes, errors for bad CSVs, and the study report.
#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "framework/core/seed.hpp"
#include "tests/analysis/reference_table.hpp"
#include "tests/support/run_cli.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_analyze_cli {

using namespace crowdlab;
using crowdlab::test::analysis_data;
using crowdlab::test::run_cli;

TEST_CASE("analysis: analyze anova --json has the documented shape and values", "[analysis][cli]") {
  const auto r = run_cli({"analyze", "anova", "--csv", analysis_data("md_12.1.csv"), "--dv", "rt",
                          "--subject", "id", "--within", "angle,noise", "--json"});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const auto j = nlohmann::json::parse(r.out);
  REQUIRE(j["effects"].size() == 3);
  CHECK(j["effects"][0]["effect"] == "angle");
  CHECK(j["effects"][1]["effect"] == "noise");
  CHECK(j["effects"][2]["effect"] == "angle:noise");
  for (const char* key : {"effect", "df1", "df2", "F", "p", "pes", "ges", "mauchly_W", "mauchly_p", "gg_eps",
                          "hf_eps", "p_gg", "p_hf"})
    for (const auto& e : j["effects"]) CHECK(e.contains(key));
  CHECK(j["effects"][1]["mauchly_W"].is_null());  // df1 = 1
  CHECK(j["effects"][1]["gg_eps"].is_null());
  CHECK(j["effects"][0]["F"].get<double>() == Approx(40.719101123595493).epsilon(1e-9));
  CHECK(j["effects"][0]["hf_eps"].get<double>() == Approx(1.2175636033006814).epsilon(1e-9));  // raw, > 1
  // Names follow --within order.
  const auto swapped = run_cli({"analyze", "anova", "--csv", analysis_data("md_12.1.csv"), "--dv", "rt",
                                "--subject", "id", "--within", "noise,angle", "--json"});
  REQUIRE(swapped.exit_code == 0);
  CHECK(nlohmann::json::parse(swapped.out)["effects"][2]["effect"] == "noise:angle");
  // The text table is APA-flavoured.
  const auto text = run_cli({"analyze", "anova", "--csv", analysis_data("md_12.1.csv"), "--dv", "rt",
                             "--subject", "id", "--within", "angle,noise"});
  REQUIRE(text.exit_code == 0);
  CHECK(text.out.find("F(2, 18) = 40.72, p < .001") != std::string::npos);
}

TEST_CASE("analysis: analyze posthoc and psychometric --json", "[analysis][cli]") {
  const auto ph =
      run_cli({"analyze", "posthoc", "--csv", analysis_data("md_12.1.csv"), "--dv", "rt", "--subject", "id",
               "--within", "angle,noise", "--effect", "angle:noise", "--method", "bonferroni", "--json"});
  INFO(ph.err);
  REQUIRE(ph.exit_code == 0);
  const auto j = nlohmann::json::parse(ph.out);
  CHECK(j["method"] == "bonferroni");
  CHECK(j["comparisons"].size() == 15);
  CHECK(j["simple_effects"].size() == 5);  // angle at 2 noise levels + noise at 3 angles
  const auto psy = run_cli({"analyze", "psychometric", "--csv", analysis_data("psychometric_trials.csv"),
                            "--subject", "participant", "--x", "distance", "--response", "collision", "--by",
                            "shoulder", "--p", "0.5,0.05", "--bootstrap", "20", "--json"});
  INFO(psy.err);
  REQUIRE(psy.exit_code == 0);
  const auto p = nlohmann::json::parse(psy.out);
  REQUIRE(p["fits"].size() == 18);
  for (const char* key : {"subject", "by", "intercept", "slope", "thresholds", "converged", "warning"})
    CHECK(p["fits"][0].contains(key));
  CHECK(p["fits"][0]["thresholds"].contains("0.5"));
  CHECK(p["fits"][0]["thresholds"].contains("0.05"));
  REQUIRE(p["groups"].size() == 3);
  CHECK(p["groups"][0]["mean"].contains("0.5"));
  CHECK(p["groups"][0]["sd"].contains("0.05"));
  CHECK(p["anova"]["df1"] == 2);
}

TEST_CASE("analysis: bad CSVs give exit code 2 and name the row and column", "[analysis][cli]") {
  const auto dir = test::scratch_dir("analyze_bad_csv");
  auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream((dir / name).string()) << text;
    return (dir / name).string();
  };
  const std::string header = "subj,A,y\n";
  const auto missing_col =
      run_cli({"analyze", "anova", "--csv", write("a.csv", header + "1,a,1\n1,b,2\n2,a,3\n2,b,1\n"), "--dv",
               "score", "--subject", "subj", "--within", "A"});
  CHECK(missing_col.exit_code == 2);
  CHECK(missing_col.err.find("score") != std::string::npos);
  const auto non_numeric =
      run_cli({"analyze", "anova", "--csv", write("b.csv", header + "1,a,1\n1,b,x2\n2,a,3\n2,b,1\n"), "--dv",
               "y", "--subject", "subj", "--within", "A"});
  CHECK(non_numeric.exit_code == 2);
  CHECK(non_numeric.err.find("b.csv:3") != std::string::npos);
  CHECK(non_numeric.err.find("'y'") != std::string::npos);
  const auto unbalanced =
      run_cli({"analyze", "anova", "--csv", write("c.csv", header + "1,a,1\n1,b,2\n2,a,3\n3,b,1\n3,a,2\n"),
               "--dv", "y", "--subject", "subj", "--within", "A"});
  CHECK(unbalanced.exit_code == 2);
  CHECK(unbalanced.err.find("subject '2'") != std::string::npos);
  CHECK(unbalanced.err.find("A=b") != std::string::npos);
  // A factor named twice is said to be so, not reported as an unbalanced design (issue 21).
  const auto twice =
      run_cli({"analyze", "anova", "--csv", write("e.csv", header + "1,a,1\n1,b,2\n2,a,3\n2,b,1\n"), "--dv",
               "y", "--subject", "subj", "--within", "A,A"});
  CHECK(twice.exit_code == 2);
  CHECK(twice.err.find("'A' is named twice") != std::string::npos);
  const auto bad_response =
      run_cli({"analyze", "psychometric", "--csv", write("d.csv", "s,x,r\n1,0.2,1\n1,0.3,2\n"), "--subject",
               "s", "--x", "x", "--response", "r"});
  CHECK(bad_response.exit_code == 2);
  CHECK(bad_response.err.find("d.csv:3") != std::string::npos);
}

namespace {
using crowdlab::test::slurp;

// Simulated sessions: tidy response rows as study sessions write them.
void simulate_likert_study(const std::filesystem::path& dir) {
  std::ofstream out((dir / "responses.csv").string());
  out << "participant,block,trial,stimulus_id,density,viewpoint,method,question,response,reversed,rt_ms,"
         "practice\n";
  Rng rng(derive_seed(11, "likert-study"));
  for (int p = 1; p <= 10; ++p) {
    int trial = 0;
    const double bias = standard_normal(rng) * 0.4;
    for (const char* density : {"3.33", "6.66"})
      for (const char* viewpoint : {"V1", "V3"})
        for (const char* method : {"baseline", "ours"}) {
          ++trial;
          const std::string stim =
              std::string("density-") + density + "_viewpoint-" + viewpoint + "_method-" + method;
          const double effect =
              (std::string(method) == "ours" ? 1.2 : 0.0) - (std::string(density) == "6.66" ? 0.5 : 0);
          for (int q = 1; q <= 6; ++q) {
            const bool reverse = q % 2 == 0;
            double v = std::round(3.2 + effect + bias + 0.7 * standard_normal(rng));
            v = std::clamp(v, 1.0, 6.0);
            const double response = reverse ? 7 - v : v;
            out << p << ",1," << trial << "," << stim << "," << density << "," << viewpoint << "," << method
                << ",Q" << q << "," << response << "," << (reverse ? 7 - response : response) << ",1500,0\n";
          }
        }
    out << p << ",0,0,practice_x,3.33,V1,baseline,Q1,9,9,100,1\n";  // practice: ignored (even out of range)
  }
}

void simulate_pairs_study(const std::filesystem::path& dir) {
  std::ofstream out((dir / "session_all.csv").string());
  out << "participant,block,trial,stimulus_id,shoulder,distance,viewpoint,question,response,reversed,rt_ms,"
         "practice\n";
  Rng rng(derive_seed(12, "pairs-study"));
  for (int p = 1; p <= 6; ++p) {
    int trial = 0;
    for (int shoulder = 0; shoulder < 3; ++shoulder)
      for (int di = 0; di <= 10; ++di)
        for (int rep = 1; rep <= 3; ++rep) {
          ++trial;
          char dist[16];
          std::snprintf(dist, sizeof dist, "%.2f", 0.2 + 0.05 * di);
          const double thr = 0.35 + 0.05 * shoulder + 0.02 * standard_normal(rng);
          const double pc = 1.0 / (1.0 + std::exp(25.0 * (std::stod(dist) - thr)));
          const bool yes = uniform01(rng) < pc;
          const std::string stim =
              "shoulder-" + std::to_string(shoulder) + "_distance-" + dist + "_rep-" + std::to_string(rep);
          out << p << ",1," << trial << "," << stim << "," << shoulder << "," << dist << ",pair,collision,"
              << (yes ? "yes" : "no") << "," << (yes ? "yes" : "no") << ",900,0\n";
          const int nat =
              std::clamp(static_cast<int>(std::lround(4 + shoulder * 0.5 + standard_normal(rng))), 1, 7);
          out << p << ",1," << trial << "," << stim << "," << shoulder << "," << dist << ",pair,naturalness,"
              << nat << "," << nat << ",1200,0\n";
        }
  }
}
}  // namespace

TEST_CASE("analysis: analyze report writes a Markdown report with figures", "[analysis][cli]") {
  const auto base = test::scratch_dir("analyze_report");
  std::filesystem::create_directories(base / "likert");
  simulate_likert_study(base / "likert");
  const auto r = run_cli({"analyze", "report", (base / "likert").string(), "--spec",
                          (test::source_dir() / "experiments" / "demo.yaml").string(), "--out",
                          (base / "out1").string()});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const std::string md = slurp(base / "out1" / "report.md");
  for (const char* needle :
       {"### Q_CR", "### Q_CA", "### Q_OR", "Cronbach", "| method |", "density:viewpoint:method",
        "Kolmogorov-Smirnov", "Tukey", "figures/interaction_Q_CR_density.png"})
    CHECK(md.find(needle) != std::string::npos);
  // Issue 20: each Likert item also as ordinal data (a CLMM table beside the ANOVA, and in the stats).
  for (const char* needle : {"Ordinal model of Q1", "Ordinal model of Q2", "| methodours |",
                             "| density6.66:viewpointV3:methodours |", "Random intercept SD (participant)"})
    CHECK(md.find(needle) != std::string::npos);
  CHECK(md.find("Not fitted") == std::string::npos);
  const auto stats = nlohmann::json::parse(slurp(base / "out1" / "stats" / "Q_CR.json"));
  REQUIRE(stats["clmm"].size() == 2);
  CHECK(stats["clmm"][0]["item"] == "Q1");
  CHECK(stats["clmm"][0]["fixed"].size() == 7);
  CHECK(stats["clmm"][0]["converged"] == true);
  for (const char* fig :
       {"interaction_Q_CR_density.png", "interaction_Q_CR_density.svg", "interaction_Q_OR_viewpoint.png"})
    CHECK(std::filesystem::file_size(base / "out1" / "figures" / fig) > 1000);

  std::filesystem::create_directories(base / "pairs");
  simulate_pairs_study(base / "pairs");
  const auto r2 = run_cli({"analyze", "report", (base / "pairs").string(), "--spec",
                           (test::source_dir() / "experiments" / "hoyet2016_pairs.yaml").string(), "--out",
                           (base / "out2").string()});
  INFO(r2.err);
  REQUIRE(r2.exit_code == 0);
  const std::string md2 = slurp(base / "out2" / "report.md");
  CHECK(md2.find("psychometric functions") != std::string::npos);
  CHECK(md2.find("Table 1") != std::string::npos);
  CHECK(md2.find("RM-ANOVA of the thresholds") != std::string::npos);
  CHECK(std::filesystem::file_size(base / "out2" / "figures" / "psychometric_collision.png") > 1000);
  CHECK(md2.find("### naturalness") != std::string::npos);

  // A response file without a factor column, or with an unknown question, is rejected with its name.
  std::filesystem::create_directories(base / "bad");
  std::ofstream((base / "bad" / "r.csv").string())
      << "participant,block,trial,stimulus_id,density,viewpoint,question,response,reversed,rt_ms,practice\n"
      << "1,1,1,s1,3.33,V1,Q1,3,3,100,0\n";
  const auto bad =
      run_cli({"analyze", "report", (base / "bad").string(), "--spec",
               (test::source_dir() / "experiments" / "demo.yaml").string(), "--out", (base / "o3").string()});
  CHECK(bad.exit_code == 2);
  CHECK(bad.err.find("method") != std::string::npos);
  std::ofstream((base / "bad" / "r.csv").string()) << "participant,block,trial,stimulus_id,density,viewpoint,"
                                                      "method,question,response,reversed,rt_ms,practice\n"
                                                   << "1,1,1,s1,3.33,V1,ours,Q9,3,3,100,0\n";
  const auto unknown =
      run_cli({"analyze", "report", (base / "bad").string(), "--spec",
               (test::source_dir() / "experiments" / "demo.yaml").string(), "--out", (base / "o3").string()});
  CHECK(unknown.exit_code == 2);
  CHECK(unknown.err.find("r.csv:2") != std::string::npos);
  CHECK(unknown.err.find("Q9") != std::string::npos);
}

// Issue 21: designs the ANOVA cannot analyse are refused with the file, the column and why, exit 2,
// never a Boost message, a -nan or minutes of work.
TEST_CASE("analysis: analyze refuses designs without error variance or enough subjects", "[analysis][cli]") {
  const auto dir = test::scratch_dir("analyze_degenerate");
  auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream((dir / name).string()) << text;
    return (dir / name).string();
  };
  auto anova = [](const std::string& csv) {
    return run_cli({"analyze", "anova", "--csv", csv, "--dv", "y", "--subject", "subj", "--within", "A"});
  };
  // Two subjects, five levels: the Huynh-Feldt epsilon had a negative denominator (Boost: "Degrees of
  // freedom argument is -2").
  std::string two = "subj,A,y\n";
  for (int s = 1; s <= 2; ++s)
    for (int a = 0; a < 5; ++a)
      two += std::to_string(s) + ",a" + std::to_string(a) + "," + std::to_string((a * 7 + s * 3) % 11) + "\n";
  const auto two_subjects = anova(write("two.csv", two));
  INFO(two_subjects.err);
  CHECK(two_subjects.exit_code == 2);
  CHECK(two_subjects.err.find("two.csv: 2 subjects") != std::string::npos);
  CHECK(two_subjects.err.find("at least 3") != std::string::npos);
  CHECK(two_subjects.err.find("Degrees of freedom") == std::string::npos);

  const auto constant = anova(write("constant.csv", "subj,A,y\n1,a,4\n1,b,4\n2,a,4\n2,b,4\n3,a,4\n3,b,4\n"));
  INFO(constant.err);
  CHECK(constant.exit_code == 2);
  CHECK(constant.out.find("nan") == std::string::npos);
  CHECK(constant.err.find("constant.csv: column 'y'") != std::string::npos);
  CHECK(constant.err.find("constant") != std::string::npos);

  // Every subject differs by exactly +1 between the levels: zero error, F = 1/0.
  const auto no_error = anova(write("no_error.csv", "subj,A,y\n1,a,1\n1,b,2\n2,a,2\n2,b,3\n3,a,3\n3,b,4\n"));
  INFO(no_error.err);
  CHECK(no_error.exit_code == 2);
  CHECK(no_error.err.find("no_error.csv: column 'y'") != std::string::npos);
  CHECK(no_error.err.find("'A' has zero error variance") != std::string::npos);
}

TEST_CASE("analysis: analyze refuses designs past --max-levels, --max-cells and --max-comparisons",
          "[analysis][cli]") {
  const auto dir = test::scratch_dir("analyze_limits");
  // Every row its own subject and level (an id column given as a factor): refused from the level count.
  {
    std::ofstream out((dir / "unique.csv").string());
    out << "subj,A,y\n";
    for (int i = 0; i < 3000; ++i) out << "s" << i << ",a" << i << "," << i % 7 << "\n";
  }
  const auto unique = run_cli({"analyze", "anova", "--csv", (dir / "unique.csv").string(), "--dv", "y",
                               "--subject", "subj", "--within", "A"});
  INFO(unique.err);
  CHECK(unique.exit_code == 2);
  CHECK(unique.err.find("unique.csv: A: factor has 3000 levels") != std::string::npos);
  CHECK(unique.err.find("--max-levels") != std::string::npos);

  // posthoc on a balanced 3000-level factor (3 subjects): it ran over 300 s (issue 21). Refused from the
  // level count, and with the level and cell limits raised, from the family's size (3000 * 2999 / 2
  // pairs), both before any work; the same for a between factor with a level per subject.
  {
    std::ofstream out((dir / "many.csv").string());
    out << "subj,G,A,y\n";
    for (int s = 0; s < 3; ++s)
      for (int i = 0; i < 3000; ++i) out << "s" << s << ",g" << s << ",a" << i << "," << (i + s) % 7 << "\n";
  }
  const std::vector<std::string> many = {"analyze",  "posthoc", "--csv",     (dir / "many.csv").string(),
                                         "--dv",     "y",       "--subject", "subj",
                                         "--within", "A",       "--effect",  "A"};
  const auto many_levels = run_cli(many);
  CHECK(many_levels.exit_code == 2);
  CHECK(many_levels.err.find("many.csv: A: factor has 3000 levels") != std::string::npos);
  auto raised = many;
  raised.insert(raised.end(), {"--max-levels", "5000", "--max-cells", "5000"});
  const auto many_pairs = run_cli(raised);
  INFO(many_pairs.err);
  CHECK(many_pairs.exit_code == 2);
  CHECK(many_pairs.err.find("many.csv: A: post-hoc family of 4498500 comparisons") != std::string::npos);
  {
    std::ofstream out((dir / "groups.csv").string());
    out << "subj,G,A,y\n";
    for (int s = 0; s < 3000; ++s)
      for (int a = 0; a < 2; ++a)
        out << "s" << s << ",g" << s << ",a" << a << "," << (s * 7 + a * 3) % 11 << "\n";
  }
  const auto group_pairs = run_cli({"analyze",      "posthoc", "--csv",       (dir / "groups.csv").string(),
                                    "--dv",         "y",       "--subject",   "subj",
                                    "--within",     "A",       "--between",   "G",
                                    "--effect",     "G",       "--error",     "separate",
                                    "--max-levels", "5000",    "--max-cells", "5000"});
  INFO(group_pairs.err);
  CHECK(group_pairs.exit_code == 2);
  CHECK(group_pairs.err.find("groups.csv: G: post-hoc family of 4498500 comparisons") != std::string::npos);

  // A balanced 3 x 60 x 60 design: within --max-levels, past --max-cells; 60 levels make 1770 pairs.
  {
    std::ofstream out((dir / "wide.csv").string());
    out << "subj,A,B,y\n";
    for (int s = 0; s < 3; ++s)
      for (int a = 0; a < 60; ++a)
        for (int b = 0; b < 2; ++b)
          out << s << ",a" << a << ",b" << b << "," << (a * 13 + s * 5 + b) % 17 << "\n";
  }
  const std::vector<std::string> wide = {
      "--csv", (dir / "wide.csv").string(), "--dv", "y", "--subject", "subj", "--within", "A,B"};
  auto with = [&](std::vector<std::string> head, const std::vector<std::string>& tail) {
    head.insert(head.end(), wide.begin(), wide.end());
    head.insert(head.end(), tail.begin(), tail.end());
    return run_cli(head);
  };
  const auto cells = with({"analyze", "anova"}, {"--max-cells", "100"});
  INFO(cells.err);
  CHECK(cells.exit_code == 2);
  CHECK(cells.err.find("wide.csv: the design has A 60 x B 2 = 120 cells") != std::string::npos);
  CHECK(cells.err.find("--max-cells") != std::string::npos);
  const auto levels = with({"analyze", "anova"}, {"--max-levels", "50"});
  CHECK(levels.exit_code == 2);
  CHECK(levels.err.find("wide.csv: A: factor has 60 levels") != std::string::npos);
  const auto pairs = with({"analyze", "posthoc"}, {"--effect", "A"});
  INFO(pairs.err);
  CHECK(pairs.exit_code == 2);
  CHECK(pairs.err.find("wide.csv: A: post-hoc family of 1770 comparisons") != std::string::npos);
  CHECK(pairs.err.find("--max-comparisons") != std::string::npos);
  // Within the limits, the same design is analysed.
  const auto fits = with({"analyze", "anova"}, {"--json"});
  INFO(fits.err);
  CHECK(fits.exit_code == 0);
  const auto simple = with({"analyze", "posthoc"}, {"--effect", "B", "--method", "bonferroni", "--json"});
  INFO(simple.err);
  CHECK(simple.exit_code == 0);
}

}  // namespace test_analyze_cli
