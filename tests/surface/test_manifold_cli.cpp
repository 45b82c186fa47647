// The `manifold` scenario through the real binary: `crowdlab run` writes the 2D (developed) and 3D
// surface trajectories and a crowd file per condition; `crowdlab crowd` writes one condition's 3D
// trajectories; bad crowd models are rejected with exit code 2; `bench manifold --json` has its fields.
#include <catch2/catch.hpp>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "tests/support/run_cli.hpp"
#include "tests/support/test_paths.hpp"

using namespace crowdlab;
namespace fs = std::filesystem;

namespace {

fs::path write_spec(const fs::path& dir, const std::string& model) {
  const fs::path spec = dir / ("manifold_" + model + ".yaml");
  std::ofstream(spec) << "crowdlab: 1\nname: manifold_cli\nseed: 3\n"
                         "scenario: {type: manifold, mesh: floor_wall, agents: 6}\n"
                         "crowd: {model: " +
                             model +
                             ", neighbor_distance_m: 3.0}\n"
                             "factors:\n  method: [baseline]\n"
                             "duration_s: 0.6\nfps: 10\nresolution: [64, 36]\n"
                             "protocol: {type: likert, questions: [{id: Q1, text: q}]}\n"
                             "outputs: {video: false, contact_sheet: false}\n";
  return spec;
}

size_t line_count(const fs::path& p) {
  std::ifstream in(p);
  std::string line;
  size_t n = 0;
  while (std::getline(in, line)) ++n;
  return n;
}

}  // namespace

TEST_CASE("crowdlab run on a manifold spec writes surface trajectories and a crowd file") {
  const fs::path dir = test::scratch_dir("manifold_cli");
  const auto r = test::run_cli({"run", write_spec(dir, "orca").string(), "--out", (dir / "out").string()});
  INFO(r.out << r.err);
  REQUIRE(r.exit_code == 0);
  const fs::path crowd = dir / "out" / "crowds" / "rep-1";  // method does not change the crowd
  // 6 agents x 6 frames + header, in both files.
  CHECK(line_count(crowd / "trajectories.csv") == 37);
  CHECK(line_count(crowd / "surface_trajectories.csv") == 37);
  CHECK(fs::file_size(crowd / "baseline.glb") > 1000);
  CHECK(fs::exists(dir / "out" / "manifest.csv"));
  // Resumable: a second run is up to date.
  const auto again =
      test::run_cli({"run", write_spec(dir, "orca").string(), "--out", (dir / "out").string()});
  CHECK(again.exit_code == 0);
  CHECK(again.out.find("0 stage outputs made") != std::string::npos);

  const auto one = test::run_cli({"crowd", write_spec(dir, "social").string(), "--condition",
                                  "method-baseline_rep-1", "--csv", (dir / "one.csv").string()});
  INFO(one.err);
  CHECK(one.exit_code == 0);
  CHECK(line_count(dir / "one.csv") == 37);

  const auto bad = test::run_cli({"run", write_spec(dir, "cost").string(), "--out", (dir / "bad").string()});
  CHECK(bad.exit_code == 2);
  CHECK(bad.err.find("crowd.model") != std::string::npos);
}

TEST_CASE("bench manifold --json reports its fields for both models") {
  for (const std::string model : {"social", "orca"}) {
    const auto r = test::run_cli({"bench", "manifold", "--agents", "20", "--mesh", "floor_wall", "--steps",
                                  "3", "--model", model, "--json"});
    INFO(r.err);
    REQUIRE(r.exit_code == 0);
    const auto j = nlohmann::json::parse(r.out);
    CHECK(j.at("agents") == 20);
    CHECK(j.at("triangles").get<int>() > 0);
    CHECK(j.at("ms_per_step_median").get<double>() > 0);
    CHECK(j.at("model") == model);
  }
}
