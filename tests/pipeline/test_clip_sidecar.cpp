// One camera per condition (issue 17): `crowdlab run` frames `baseline` and `ours` of a condition from
// the data they share, and each clip's sidecar (clip.json) records that camera and the characters.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>

#include "framework/core/sha256.hpp"
#include "framework/core/stimulus_manifest.hpp"
#include "tests/support/run_cli.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_clip_sidecar {

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
    // The stimulus check (issue 28): measured for every clip, the same numbers in the manifest.
    const json& check = base.at("stimulus_check");
    CHECK(check.at("crowd_in_frame_min").get<double>() >= 0.0);
    CHECK(check.at("crowd_in_frame_min").get<double>() <= 1.0);
    CHECK(check.at("character_height_px").get<double>() > 0.0);
    CHECK(check.at("overlap_frame_share").get<double>() >= 0.0);
    CHECK(check.at("overlap_pixel_fraction").get<double>() >= 0.0);
    CHECK(check.at("seam_step_ratio").get<double>() > 0.0);
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

TEST_CASE("run --strict and check-stimuli judge every clip by the spec's render.check") {
  const fs::path out = scratch_dir("pipeline_stimulus_check");
  // pair_cameras.yaml with a character-height limit no clip can meet.
  std::string text = slurp(source_dir() / "tests/data/pipeline/pair_cameras.yaml");
  text += "\nrender:\n  check: {character_height_px_min: 100000, overhead_height_px_min: 100000}\n";
  const fs::path spec = out / "strict.yaml";
  std::ofstream(spec) << text;
  const fs::path run_dir = out / "run";
  CliResult r = run_cli({"-q", "run", spec.string(), "--out", run_dir.string(), "--strict"});
  INFO(r.out << r.err);
  CHECK(r.exit_code == 1);
  CHECK_THAT(r.err, Catch::Contains("character height"));
  REQUIRE(fs::exists(run_dir / "manifest.csv"));  // everything is written before the failure
  for (const StimulusEntry& e : read_manifest((run_dir / "manifest.csv").string()).entries)
    CHECK(e.check.character_height_px > 0.0);
  // Without --strict the same run only warns.
  r = run_cli({"-q", "run", spec.string(), "--out", run_dir.string()});
  CHECK(r.exit_code == 0);
  // check-stimuli prints one row per clip with the verdict.
  r = run_cli({"check-stimuli", run_dir.string()});
  CHECK(r.exit_code == 0);
  CHECK_THAT(r.out,
             Catch::Contains("| density-3.5_viewpoint-V3_method-baseline_rep-1 | V3 | baseline | 3.5 |"));
  CHECK_THAT(r.out, Catch::Contains("4 clip(s): 4 outside render.check, 0 not measured"));
  r = run_cli({"check-stimuli", run_dir.string(), "--strict"});
  CHECK(r.exit_code == 1);
  // Judged by the shipped spec's default limits instead, the same clips pass.
  r = run_cli({"check-stimuli", run_dir.string(), "--spec",
               (source_dir() / "tests/data/pipeline/pair_cameras.yaml").string()});
  CHECK_THAT(r.out, Catch::Contains("4 clip(s): "));
  CHECK(r.exit_code == 0);
}

TEST_CASE("run --check-only measures every clip as a rendered run does, without making the clips") {
  const fs::path out = scratch_dir("pipeline_check_only");
  // pair_cameras.yaml denser and larger, so that the baseline shows overlap pixels and the comparison of
  // the overlap measures means something.
  std::string text = slurp(source_dir() / "tests/data/pipeline/pair_cameras.yaml");
  text = std::regex_replace(text, std::regex(R"(density: \[3\.5\])"), "density: [6.0]");
  text = std::regex_replace(text, std::regex(R"(resolution: \[160, 96\])"), "resolution: [320, 192]");
  const fs::path spec = out / "dense.yaml";
  std::ofstream(spec) << text;
  const fs::path checked = out / "checked", rendered = out / "rendered";
  CliResult r = run_cli({"-q", "run", spec.string(), "--out", checked.string(), "--check-only"});
  INFO(r.out << r.err);
  REQUIRE(r.exit_code == 0);
  r = run_cli({"-q", "run", spec.string(), "--out", rendered.string()});
  REQUIRE(r.exit_code == 0);

  std::map<std::string, StimulusEntry> by_id;
  for (const StimulusEntry& e : read_manifest((rendered / "manifest.csv").string()).entries) by_id[e.id] = e;
  const std::vector<StimulusEntry> entries = read_manifest((checked / "manifest.csv").string()).entries;
  REQUIRE(entries.size() == 4);
  for (const StimulusEntry& e : entries) {
    INFO(e.id);
    const fs::path dir = checked / "conditions" / e.id;
    CHECK(fs::exists(dir / "stimulus_check.json"));
    CHECK_FALSE(fs::exists(dir / "clip.mp4"));
    CHECK(e.file.empty());
    const StimulusCheck& c = e.check;
    const StimulusCheck& rc = by_id.at(e.id).check;
    CHECK(c.crowd_in_frame_min == rc.crowd_in_frame_min);
    CHECK(c.character_height_px == rc.character_height_px);
    CHECK(c.overlap_frame_share == rc.overlap_frame_share);
    CHECK(c.overlap_pixel_fraction == rc.overlap_pixel_fraction);
    CHECK(c.seam_step_ratio == rc.seam_step_ratio);
    if (e.factors.at("method") == "baseline") CHECK(c.overlap_pixel_fraction > 0.0);
    // The camera recorded beside the check is the one the clip was drawn with.
    const json j = read_json(dir / "stimulus_check.json");
    CHECK(j.at("camera") == read_json(rendered / "conditions" / e.id / "clip.json").at("camera"));
  }
  CHECK(fs::directory_iterator(checked / "crowds" / "density-6.0_rep-1") != fs::directory_iterator());
  for (const auto& f : fs::directory_iterator(checked / "crowds" / "density-6.0_rep-1"))
    CHECK(f.path().string().find("contact_sheet") == std::string::npos);
  // Up to date on a second run; check-stimuli reads it as a rendered run's.
  r = run_cli({"-q", "run", spec.string(), "--out", checked.string(), "--check-only"});
  CHECK_THAT(r.out, Catch::Contains("0 stage outputs made"));
  r = run_cli({"check-stimuli", checked.string()});
  CHECK_THAT(r.out, Catch::Contains("4 clip(s): "));
  CHECK_THAT(r.out, Catch::Contains(", 0 not measured"));
}

}  // namespace test_clip_sidecar
