// Each stage of `crowdlab run` is redone exactly when something it reads changed (issue 30): after a
// first run of a one-crowd spec (both methods, contact sheets on), the spec is edited one value at a
// time and run again, and the outputs whose provenance records a new input hash must be exactly the
// edited stage's and its dependants'. Before the recipes, the crowd, animation and render stages hashed
// the whole YAML text, so a text-only protocol edit redid every crowd, animation and clip; and the
// contact sheets hashed only the image size, so a background change left them stale.
// Driven through the binary, as a user would (tiny scale: 1 s at 15 fps, 160 x 96).
#include <unistd.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "tests/support/run_cli.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_stage_redo {

using namespace crowdlab;
using namespace crowdlab::test;
namespace fs = std::filesystem;

namespace {

// One crowd group: one density, one viewpoint, both methods.
const std::string kBaseSpec = R"(crowdlab: 1
name: redo
seed: 7
scenario:
  type: stationary
  area: {width_m: 1.5, depth_m: 1.5}
crowd:
  agent_radius_m: 0.18
animation:
  female_fraction: 0.5
correction:
  damping: 0.006
render:
  crf: 18
  background: "#d8dde3"
factors:
  density: [3.0]
  viewpoint: [V4]
  method: [baseline, ours]
repetitions: 1
duration_s: 1.0
fps: 15
resolution: [160, 96]
protocol:
  type: likert
  instructions: "Watch each clip."
  scale: {points: 6, labels: ["I strongly disagree", "I fully agree"]}
  questions:
    - {id: Q1, text: "Contacts made by characters between them seem natural to me"}
outputs:
  video: true
  contact_sheet: true
)";

// The outputs of the one crowd group, by stage.
const std::string kGroup = "crowds/density-3.0_rep-1/";
const std::string kCondition = "conditions/density-3.0_viewpoint-V4_method-";
const std::string kCrowd = kGroup + "trajectories.csv";
const std::string kBaseline = kGroup + "baseline.glb";
const std::string kOurs = kGroup + "ours.glb";
const std::string kMetricsBaseline = kGroup + "baseline.metrics.json";
const std::string kMetricsOurs = kGroup + "ours.metrics.json";
const std::string kClipBaseline = kCondition + "baseline_rep-1/clip.mp4";
const std::string kClipOurs = kCondition + "ours_rep-1/clip.mp4";
const std::string kSheetBaseline = kGroup + "baseline.contact_sheet.png";
const std::string kSheetOurs = kGroup + "ours.contact_sheet.png";
const std::string kClipJsonBaseline = kCondition + "baseline_rep-1/clip.json";
const std::string kClipJsonOurs = kCondition + "ours_rep-1/clip.json";
const std::set<std::string> kClips{kClipBaseline, kClipJsonBaseline, kClipOurs, kClipJsonOurs};
const std::set<std::string> kSheets{kSheetBaseline, kSheetOurs};

std::set<std::string> operator+(std::set<std::string> a, const std::set<std::string>& b) {
  a.insert(b.begin(), b.end());
  return a;
}

/// `text` with `from` (which must occur) replaced by `to`.
std::string edited(const std::string& text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.substr(0, at) + to + text.substr(at + from.size());
}

/// Every output of a run folder (relative path) with the input hash its provenance sidecar records.
std::map<std::string, std::string> input_hashes(const fs::path& root) {
  std::map<std::string, std::string> hashes;
  const std::string suffix = ".prov.json";
  for (const auto& e : fs::recursive_directory_iterator(root)) {
    const std::string path = e.path().generic_string();
    if (!e.is_regular_file() || !path.ends_with(suffix)) continue;
    std::ifstream in(e.path());
    const std::string output = fs::relative(e.path(), root).generic_string();
    hashes[output.substr(0, output.size() - suffix.size())] =
        nlohmann::json::parse(in).value("input_hash", "");
  }
  return hashes;
}

void run_spec(const std::string& yaml, const fs::path& spec, const fs::path& out) {
  {
    std::ofstream f(spec, std::ios::binary | std::ios::trunc);
    f << yaml;
  }
  const CliResult r = run_cli({"-q", "run", spec.string(), "--out", out.string()});
  INFO(r.out << r.err);
  REQUIRE(r.exit_code == 0);
}

/// A scratch folder of this process (ctest may run several test cases of this file at once).
fs::path own_scratch(const std::string& name) {
  return scratch_dir(name + "_" + std::to_string(::getpid()));
}

/// The outputs remade when the first run's spec is edited from `from` to `to` and run again.
std::set<std::string> redone_after(const fs::path& first_run, const std::string& from,
                                   const std::string& to) {
  const fs::path dir = own_scratch("stage_redo_edit");
  fs::copy(first_run, dir / "out", fs::copy_options::recursive);
  const auto before = input_hashes(dir / "out");
  run_spec(edited(kBaseSpec, from, to), dir / "spec.yaml", dir / "out");
  std::set<std::string> redone;
  for (const auto& [output, hash] : input_hashes(dir / "out")) {
    const auto it = before.find(output);
    if (it == before.end() || it->second != hash) redone.insert(output);
  }
  return redone;
}

/// The first run, made once for every case.
const fs::path& first_run() {
  static const fs::path out = [] {
    const fs::path dir = own_scratch("stage_redo_first");
    run_spec(kBaseSpec, dir / "spec.yaml", dir / "out");
    return dir / "out";
  }();
  return out;
}

}  // namespace

TEST_CASE("stage redo: a text-only protocol edit redoes no stage, and the contact sheets are made",
          "[pipeline][redo]") {
  const auto made = input_hashes(first_run());
  for (const std::string& file : std::set<std::string>{kCrowd, kBaseline, kOurs, kMetricsBaseline,
                                                       kMetricsOurs, kSheetBaseline, kSheetOurs} +
                                     kClips) {
    INFO(file);
    CHECK(made.count(file) == 1);
  }
  CHECK(redone_after(first_run(), "name: redo", "name: redo").empty());
  // Text the stages do not read: the study's wording, the spec's name.
  CHECK(redone_after(first_run(), "Watch each clip.", "Watch every clip closely.").empty());
  CHECK(redone_after(first_run(), "seem natural to me", "look natural to me").empty());
  CHECK(redone_after(first_run(), "I fully agree", "I agree completely").empty());
  CHECK(redone_after(first_run(), "name: redo", "name: redo_renamed").empty());

  // The contact sheets: V1-V4 tiles of the shown crowd, together the clip's size.
  for (const std::string& sheet : {kSheetBaseline, kSheetOurs}) {
    INFO(sheet);
    const std::string png = slurp(first_run() / sheet);
    REQUIRE(png.size() > 24);
    CHECK(png.substr(1, 3) == "PNG");
    // IHDR: width and height, big-endian, at bytes 16..23.
    auto be32 = [&png](size_t at) {
      return (static_cast<unsigned char>(png[at]) << 24) | (static_cast<unsigned char>(png[at + 1]) << 16) |
             (static_cast<unsigned char>(png[at + 2]) << 8) | static_cast<unsigned char>(png[at + 3]);
    };
    CHECK(be32(16) == 160);
    CHECK(be32(20) == 96);
  }
  // Turning the sheets off makes none and redoes nothing else.
  CHECK(redone_after(first_run(), "contact_sheet: true", "contact_sheet: false").empty());
}

TEST_CASE("stage redo: the stimuli's look redoes the clips and the contact sheets, the encoding the clips",
          "[pipeline][redo]") {
  const std::set<std::string> look = kClips + kSheets;
  CHECK(redone_after(first_run(), "background: \"#d8dde3\"", "background: \"#202020\"") == look);
  CHECK(redone_after(first_run(), "crf: 18", "crf: 18\n  fog: true") == look);
  CHECK(redone_after(first_run(), "crf: 18", "crf: 18\n  overlap: true") == look);
  CHECK(redone_after(first_run(), "crf: 18", "crf: 18\n  msaa: 4") == look);
  CHECK(redone_after(first_run(), "crf: 18", "crf: 18\n  viewpoints: {V4: [0, 12, 1, 0, 0, 0, 40]}") == look);
  CHECK(redone_after(first_run(), "resolution: [160, 96]", "resolution: [192, 96]") == look);
  CHECK(redone_after(first_run(), "crf: 18", "crf: 23") == kClips);
}

TEST_CASE("stage redo: a crowd, animation or correction change redoes its stage and exactly its dependants",
          "[pipeline][redo]") {
  CHECK(redone_after(first_run(), "damping: 0.006", "damping: 0.02") ==
        std::set<std::string>{kOurs, kMetricsOurs, kClipOurs, kClipJsonOurs, kSheetOurs});
  CHECK(redone_after(first_run(), "female_fraction: 0.5", "female_fraction: 0.2") ==
        std::set<std::string>{kBaseline, kOurs, kMetricsBaseline, kMetricsOurs} + kClips + kSheets);
  CHECK(redone_after(first_run(), "width_m: 1.5", "width_m: 1.6") ==
        std::set<std::string>{kCrowd, kBaseline, kOurs, kMetricsBaseline, kMetricsOurs} + kClips + kSheets);
  // Values a stationary crowd does not read (the walking speed, the navigation model's) redo nothing:
  // the crowd recipe holds only what its scenario kind reads.
  CHECK(redone_after(first_run(), "agent_radius_m: 0.18",
                     "agent_radius_m: 0.18\n  model: social\n  max_speed_mps: 2.0\n  dt_s: 0.05")
            .empty());
  CHECK(redone_after(first_run(), "area: {width_m: 1.5, depth_m: 1.5}",
                     "area: {width_m: 1.5, depth_m: 1.5}\n  walk_speed_mps: 1.1\n  passing_side: right")
            .empty());
}

}  // namespace test_stage_redo
