// The `manifold` scenario through the real binary: `crowdlab run` writes the 2D (developed) and 3D
// surface trajectories and a crowd file per condition; `crowdlab crowd` writes one condition's 3D
// trajectories; bad crowd models are rejected with exit code 2; `bench manifold --json` has its fields.
#include <catch2/catch.hpp>

#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <vector>

#include "tests/support/run_cli.hpp"
#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_manifold_cli {

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
    CHECK(j.at("relevant") == "visibility");
    CHECK(j.at("body_up") == "smooth");
  }
  const auto r = test::run_cli({"bench", "manifold", "--agents", "20", "--mesh", "floor_ceiling", "--steps",
                                "3", "--relevant", "visibility_mesh", "--face-up", "--json"});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const auto j = nlohmann::json::parse(r.out);
  CHECK(j.at("relevant") == "visibility_mesh");
  CHECK(j.at("body_up") == "face");
  CHECK(test::run_cli({"bench", "manifold", "--relevant", "disk"}).exit_code != 0);
}

TEST_CASE("experiment manifold-compare measures every scene, model and Relevant function") {
  const fs::path out = test::scratch_dir("manifold_compare_cli");
  const auto r = test::run_cli({"experiment", "manifold-compare", "--agents", "60", "--steps", "30", "--runs",
                                "1", "--out", out.string()});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  std::ifstream in(out / "manifold_compare.csv");
  std::string line;
  std::getline(in, line);
  std::map<std::string, std::vector<double>> rows;  // "scene model relevant" -> collisions %, FP, FN
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::vector<std::string> f;
    for (std::string cell; std::getline(ss, cell, ',');) f.push_back(cell);
    REQUIRE(f.size() == 9);
    rows[f[0] + " " + f[1] + " " + f[2]] = {std::stod(f[6]), std::stod(f[7]), std::stod(f[8])};
  }
  CHECK(rows.size() == 3 * 2 * 4);
  for (const auto& [key, v] : rows) {
    INFO(key);
    CHECK(v[0] >= 0);
    CHECK(v[0] <= 100);
  }
  for (const std::string model : {"social", "orca"}) {
    // Seed 002 Fig. 2: the Euclidean baseline avoids agents through the slab; the visibility tests do
    // not (the refinement tests the real mesh where the disk stands for it).
    CHECK(rows.at("floor_ceiling " + model + " euclidean")[1] > 0.1);
    CHECK(rows.at("floor_ceiling " + model + " visibility")[1] < 0.01);
    CHECK(rows.at("floor_ceiling " + model + " visibility_mesh")[1] < 0.01);
  }
  CHECK(r.out.find("median collision rate, visibility_mesh Relevant") != std::string::npos);
}

}  // namespace test_manifold_cli
