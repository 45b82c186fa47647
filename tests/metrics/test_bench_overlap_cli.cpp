// `crowdlab bench overlap --json` prints one JSON object with the timing keys; bad arguments exit 2.
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "tests/support/run_cli.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_bench_overlap_cli {

using namespace crowdlab;

TEST_CASE("crowdlab bench overlap --json prints one object with its timings") {
  const test::CliResult r = test::run_cli({"bench", "overlap", "--pairs", "3", "--repeats", "1", "--json"});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const nlohmann::json j = nlohmann::json::parse(r.out);
  CHECK(j.at("pairs").get<int>() == 3);
  CHECK(j.at("ms_per_pair_median").get<double>() > 0.0);
  CHECK(j.at("ms_per_pair_mean").get<double>() > 0.0);
  CHECK(j.at("mean_volume_l").get<double>() > 0.0);
  CHECK(j.at("mean_error_bound_l").get<double>() >= 0.0);
  CHECK(test::run_cli({"bench", "overlap", "--pairs", "0"}).exit_code == 2);
}

}  // namespace test_bench_overlap_cli
