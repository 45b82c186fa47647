// One camera per condition (issue 17): `crowdlab run` frames `baseline` and `ours` of a condition from
// the data they share, and each clip's sidecar (clip.json) records that camera and the characters.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "framework/core/sha256.hpp"
#include "framework/core/stimulus_manifest.hpp"
#include "tests/support/run_cli.hpp"

using namespace crowdlab;
using namespace crowdlab::test;
namespace fs = std::filesystem;
using nlohmann::json;

namespace {
json read_json(const fs::path& path) {
  std::ifstream in(path);
  REQUIRE(in);
  return json::parse(in);
}
}  // namespace

TEST_CASE("baseline and ours of a condition are rendered with the identical camera") {
  const fs::path out = scratch_dir("pipeline_pair_cameras");
  const std::string spec = (source_dir() / "tests/data/pipeline/pair_cameras.yaml").string();
  CliResult r = run_cli({"-q", "run", spec, "--out", out.string()});
  INFO(r.out << r.err);
  REQUIRE(r.exit_code == 0);
  // The correction moved the bodies, so framing each crowd file on its own would differ.
  const fs::path crowds = out / "crowds" / "density-3.5_rep-1";
  REQUIRE(sha256_file_hex((crowds / "baseline.glb").string()) !=
          sha256_file_hex((crowds / "ours.glb").string()));

  std::map<std::string, std::map<std::string, json>> sidecars;  // viewpoint -> method -> sidecar
  for (const StimulusEntry& e : read_manifest((out / "manifest.csv").string()).entries) {
    const fs::path sidecar = out / fs::path(e.file).replace_extension(".json");
    REQUIRE(fs::exists(sidecar));
    CHECK(fs::exists(sidecar.string() + ".prov.json"));
    sidecars[e.factors.at("viewpoint")][e.factors.at("method")] = read_json(sidecar);
  }
  REQUIRE(sidecars.size() == 2);
  for (const auto& [viewpoint, by_method] : sidecars) {
    INFO("viewpoint " << viewpoint);
    const json& base = by_method.at("baseline");
    const json& ours = by_method.at("ours");
    CHECK(base.at("format") == "crowdlab-clip/1");
    CHECK(base.at("viewpoint") == viewpoint);
    CHECK(base.at("frames") == 15);
    CHECK(base.at("camera").at("width") == 160);
    CHECK(base.at("camera").at("height") == 96);
    CHECK(base.at("camera").at("eye").size() == 3);
    CHECK(base.at("camera") == ours.at("camera"));
    CHECK(base.at("camera").at("moves") == (viewpoint == "tracking"));
    CHECK(base.contains("camera_per_frame") == (viewpoint == "tracking"));
    if (viewpoint == "tracking") {
      REQUIRE(base.at("camera_per_frame").size() == 15);
      CHECK(base.at("camera_per_frame") == ours.at("camera_per_frame"));
    }
    // Every character is listed with its sex and height; the correction changes neither.
    REQUIRE(!base.at("characters").empty());
    CHECK(base.at("characters") == ours.at("characters"));
    for (const json& c : base.at("characters")) {
      CHECK((c.at("sex") == "female" || c.at("sex") == "male"));
      CHECK(c.at("height_m").get<double>() > 1.2);
      CHECK(c.at("height_m").get<double>() < 2.3);
    }
  }

  // A lost sidecar is written again without re-rendering its clip.
  const StimulusEntry first = read_manifest((out / "manifest.csv").string()).entries.front();
  const fs::path sidecar = out / fs::path(first.file).replace_extension(".json");
  const json before = read_json(sidecar);
  fs::remove(sidecar);
  r = run_cli({"-q", "run", spec, "--out", out.string()});
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.out, Catch::Contains("0 stage outputs made"));
  CHECK(read_json(sidecar) == before);
}
