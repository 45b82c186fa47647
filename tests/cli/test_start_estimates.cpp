// Issue 33: the commands whose accepted options allow hours of work print an estimate of their time and
// memory before any work (experiments/cli/command_estimates.hpp), then progress lines with the time left.
// Before, `metrics --base-cells 4096 --depth 12`, `bench crowd --agents 100000 --steps 100000`,
// `experiment manifold-compare --agents 100000`, `simulate-study --observers 100000`, `power --n
// 1000000000`, `power --simulations 1000000000`, `render --synthetic 10000` and `bench correct
// --characters 10000` printed an estimate only after 2 s of work (Progress), and `power --n 1000000000`
// never (its progress counted whole simulated studies). Each test runs the command on a small input and
// checks the order of the lines on stderr, never a time: the estimate comes before the first progress
// line ("started"). The work limits that refuse outright (render --synthetic 100000000, bench correct
// --characters 1000000) are tested in tests/core/test_untrusted_inputs.cpp.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "framework/io/write_crowd_glb.hpp"
#include "stimuli/synthetic_crowd.hpp"
#include "tests/study/study_fixture.hpp"
#include "tests/support/run_cli.hpp"
#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_start_estimates {

using namespace crowdlab;
namespace fs = std::filesystem;

namespace {

/// The command succeeded and its estimate ("LABEL: estimated before starting: about T and M MB of memory
/// for N UNITS") is on stderr before its first progress line.
void check_estimate_before_work(const test::CliResult& r, const std::string& label,
                                const std::string& units) {
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const std::string head = "[crowdlab] " + label + ": estimated before starting: about ";
  const auto estimate = r.err.find(head);
  const auto started = r.err.find(": started (");
  REQUIRE(estimate != std::string::npos);
  REQUIRE(started != std::string::npos);
  CHECK(estimate < started);
  const std::string line = r.err.substr(estimate, r.err.find('\n', estimate) - estimate);
  CHECK_THAT(line, Catch::Contains(" MB of memory for ") && Catch::Contains(" " + units + " "));
}

std::string synthetic_crowd_file(const fs::path& dir, int characters, int frames) {
  stimuli::SyntheticCrowdOptions co;
  co.characters = characters;
  co.frames = frames;
  co.spacing_m = 0.4;  // touching neighbours: the overlap quadrature has pairs to integrate
  const std::string path = (dir / "crowd.glb").string();
  write_crowd_glb(stimuli::make_synthetic_crowd(co), path);
  return path;
}

const char* kLikertSpec = R"(crowdlab: 1
name: estimate-test
seed: 3
factors:
  method: [baseline, ours]
  viewpoint: [V1, V3]
protocol:
  type: likert
  scale: {points: 6, labels: ["I strongly disagree", "I fully agree"]}
  questions:
    - {id: Q1, text: "Contacts made by characters between them seem natural to me"}
    - {id: Q2, text: "Character bodies overlap, it is not physically realistic to me", reverse: true}
  composites:
    - {id: Q_CR, items: [Q1, Q2]}
)";

}  // namespace

TEST_CASE("cli: metrics prints its estimate before measuring, and refuses a quadrature off its range by name",
          "[cli]") {
  const fs::path dir = test::scratch_dir("estimate-metrics");
  const std::string crowd = synthetic_crowd_file(dir, 3, 4);
  check_estimate_before_work(test::run_cli({"metrics", crowd, "--base-cells", "16", "--depth", "2"}),
                             "metrics " + crowd, "colliding pair-frames");
  // The quadrature refused these only at the first colliding pair, without the option's name
  // ("overlap_volume: options need 0 <= depth <= 12 ..."), and a crowd without contacts passed them.
  const auto depth = test::run_cli({"metrics", crowd, "--depth", "13"});
  CHECK(depth.exit_code == 2);
  CHECK_THAT(depth.err, Catch::Contains("--depth: must be 0 to 12, got 13"));
  const auto cells = test::run_cli({"metrics", crowd, "--base-cells", "4097"});
  CHECK(cells.exit_code == 2);
  CHECK_THAT(cells.err, Catch::Contains("--base-cells: must be 1 to 4096, got 4097"));
}

TEST_CASE("cli: bench crowd prints its estimate before the warm-up", "[cli]") {
  check_estimate_before_work(test::run_cli({"bench", "crowd", "--agents", "40", "--steps", "3"}),
                             "bench crowd", "agent-steps");
}

TEST_CASE("cli: experiment manifold-compare prints its estimate before the first run", "[cli]") {
  const fs::path dir = test::scratch_dir("estimate-manifold");
  check_estimate_before_work(test::run_cli({"experiment", "manifold-compare", "--agents", "10", "--steps",
                                            "2", "--runs", "1", "--out", (dir / "out").string()}),
                             "manifold-compare", "agent-steps");
}

TEST_CASE("cli: simulate-study and power print their estimates before the first observer", "[cli]") {
  const fs::path dir = test::scratch_dir("estimate-study");
  test::make_stimuli(dir / "stimuli", {{"method", {"baseline", "ours"}}, {"viewpoint", {"V1", "V3"}}});
  const fs::path spec = dir / "spec.yaml";
  std::ofstream(spec) << kLikertSpec;
  fs::remove_all(dir / "sim");
  check_estimate_before_work(
      test::run_cli({"simulate-study", spec.string(), "--stimuli", (dir / "stimuli").string(), "--observers",
                     "3", "--out", (dir / "sim").string()}),
      "simulating observers", "observer-trials");
  const auto power =
      test::run_cli({"power", spec.string(), "--stimuli", (dir / "stimuli").string(), "--contrast",
                     "method:baseline,ours", "--n", "3,4", "--simulations", "2"});
  check_estimate_before_work(power, "power", "observer-stimulus answers");
  // 2 simulations x (3 + 4) observers x 4 stimuli at either level of the contrast.
  CHECK_THAT(power.err, Catch::Contains("for 56 observer-stimulus answers"));
  // Progress counts observers, not whole simulated studies (one study of --n 1000000000 takes hours).
  CHECK_THAT(power.err, Catch::Contains("power n=3: started (6 steps)"));
}

TEST_CASE("cli: render prints its estimate before building and drawing the crowd", "[cli]") {
  const fs::path dir = test::scratch_dir("estimate-render");
  const std::string out = (dir / "clip.mp4").string();
  check_estimate_before_work(test::run_cli({"render", "--synthetic", "2", "--max-frames", "3", "--width",
                                            "160", "--height", "96", "--out", out}),
                             "render " + out, "character-frames");
}

TEST_CASE("cli: bench correct prints its estimate before building the fixture", "[cli]") {
  const auto r = test::run_cli({"bench", "correct", "--characters", "4", "--steps", "2", "--warmup", "1"});
  check_estimate_before_work(r, "bench correct", "character-frames");
  CHECK_THAT(r.err, Catch::Contains("for 12 character-frames"));
}

}  // namespace test_start_estimates
