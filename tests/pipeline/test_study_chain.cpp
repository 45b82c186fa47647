// Spec -> stimuli -> simulated study -> report, through the real binary: the stages must agree on
// the response format. (This caught the analysis reading reverse-keyed items raw, which cancelled
// every composite to the scale midpoint and hid the method effect.)
#include <catch2/catch.hpp>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "tests/support/run_cli.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_study_chain {

using namespace crowdlab::test;
namespace fs = std::filesystem;

TEST_CASE("simulated observers analysed by the report: paired items agree and the method effect shows") {
  const fs::path dir = scratch_dir("pipeline_study_chain");
  const std::string spec = (source_dir() / "tests/data/pipeline/tiny.yaml").string();
  REQUIRE(run_cli({"-q", "run", spec, "--out", (dir / "stimuli").string()}).exit_code == 0);
  CliResult r = run_cli({"-q", "simulate-study", spec, "--stimuli", (dir / "stimuli").string(), "--observers",
                         "10", "--out", (dir / "study").string()});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  r = run_cli({"-q", "analyze", "report", (dir / "study").string(), "--spec", spec, "--out",
               (dir / "report").string()});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);

  std::ifstream md_in(dir / "report" / "report.md");
  std::stringstream md;
  md << md_in.rdbuf();
  // Q1 and the reverse-coded Q2 measure the same thing: their reliability must be clearly positive.
  const std::string text = md.str();
  const std::string key = "Cronbach's α = ";
  const size_t at = text.find(key);
  REQUIRE(at != std::string::npos);
  CHECK(std::stod(text.substr(at + key.size(), 12)) > 0.5);

  std::ifstream json_in(dir / "report" / "stats" / "Q_CR.json");
  const nlohmann::json stats = nlohmann::json::parse(json_in);
  bool found = false;
  for (const auto& e : stats["anova"]["effects"])
    if (e["effect"] == "method") {
      found = true;
      CHECK(e["p"].get<double>() < 0.05);  // corrected crowds overlap less: observers rate contacts better
    }
  CHECK(found);
}

}  // namespace test_study_chain
