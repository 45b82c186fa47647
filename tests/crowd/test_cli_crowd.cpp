// The real `crowdlab` binary: crowd trajectories for a condition, measures, errors, bench JSON.
#include <catch2/catch.hpp>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "framework/core/csv.hpp"
#include "framework/spec/load_experiment_spec.hpp"
#include "tests/support/run_cli.hpp"
#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_cli_crowd {

using namespace crowdlab;

TEST_CASE("cli: crowd writes one condition's trajectories and measures", "[crowd][cli]") {
  const auto dir = test::scratch_dir("cli_crowd");
  const std::string spec = (test::source_dir() / "experiments" / "demo.yaml").string();
  const auto list = test::run_cli({"crowd", spec, "--list"});
  REQUIRE(list.exit_code == 0);
  const std::string first = list.out.substr(0, list.out.find('\n'));
  REQUIRE(first.find("density-") == 0);
  const auto r = test::run_cli({"crowd", spec, "--condition", first, "--csv", (dir / "t.csv").string(),
                                "--measures", (dir / "m").string()});
  REQUIRE(r.exit_code == 0);
  const auto summary = nlohmann::json::parse(r.out);
  const int n = summary["characters"].get<int>();
  const int frames = summary["frames"].get<int>();
  CHECK(n == 21);  // 3.33 per m^2 on 2.5 m x 2.5 m
  const ExperimentSpec demo = load_experiment_spec(spec);
  CHECK(frames == static_cast<int>(std::lround(demo.duration_s * demo.fps)));
  const CsvTable t = read_csv((dir / "t.csv").string());
  CHECK(t.rows.size() == static_cast<std::size_t>(n * frames));
  CHECK(t.header.at(3) == "x");
  CHECK(t.header.at(5) == "heading_rad");
  for (const char* f : {"collisions.csv", "pairs.csv", "distances.csv", "summary.json"})
    CHECK(std::filesystem::exists(dir / "m" / f));
  CHECK(read_csv((dir / "m" / "pairs.csv").string()).has_column("ttca_s"));
}

TEST_CASE("cli: crowd rejects unknown conditions and missing outputs with exit code 2", "[crowd][cli]") {
  const std::string spec = (test::source_dir() / "experiments" / "demo.yaml").string();
  const auto bad = test::run_cli({"crowd", spec, "--condition", "nope", "--csv", "x.csv"});
  CHECK(bad.exit_code == 2);
  CHECK(bad.err.find("no condition 'nope'") != std::string::npos);
  CHECK(test::run_cli({"crowd", spec}).exit_code == 2);
  CHECK(test::run_cli({"crowd", "/nonexistent.yaml", "--list"}).exit_code == 2);
}

TEST_CASE("cli: bench crowd prints one JSON object", "[crowd][cli]") {
  for (const char* model : {"orca", "social", "cost"}) {
    const auto r =
        test::run_cli({"bench", "crowd", "--model", model, "--agents", "60", "--steps", "4", "--json"});
    REQUIRE(r.exit_code == 0);
    const auto j = nlohmann::json::parse(r.out);
    CHECK(j["agents"] == 60);
    CHECK(j["threads"] == 1);
    CHECK(j["steps"] == 4);
    CHECK(j["ms_per_step_median"].get<double>() > 0.0);
    CHECK(j.contains("ms_per_step_mean"));
  }
  CHECK(test::run_cli({"bench", "crowd", "--model", "rvo9"}).exit_code == 2);
  CHECK(test::run_cli({"bench", "crowd", "--agents", "1"}).exit_code == 2);
}

}  // namespace test_cli_crowd
