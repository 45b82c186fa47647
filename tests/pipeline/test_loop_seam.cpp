// Looping clips of `ours` (issue 28, item 5): `run` corrects a looping crowd with the loop pre-roll, so
// the clip's last-to-first step is no larger than 1.5x its median frame step, and the loop closure keeps
// planted feet where they stand (stance-foot drift within `reproduce gomez2024`'s 10 mm) and adds no joint
// flips (the closures, whole-crowd or per character, must add none).
#include <catch2/catch.hpp>
#include <filesystem>

#include "framework/core/stimulus_manifest.hpp"
#include "tests/support/run_cli.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_loop_seam {

using namespace crowdlab;
using namespace crowdlab::test;
namespace fs = std::filesystem;

TEST_CASE("ours loops without a seam, keeps its planted feet and flips no joint", "[pipeline][loop]") {
  // 4 s (closed over 2 s) and 2 s (the shortest clip closed, over 1 s: the demo's clips; session 26).
  const std::string name = GENERATE(as<std::string>{}, "loop_seam", "loop_seam_2s");
  const fs::path out = scratch_dir("pipeline_" + name);
  const std::string spec = (source_dir() / "tests/data/pipeline" / (name + ".yaml")).string();
  const CliResult r = run_cli({"-q", "run", spec, "--out", out.string()});
  INFO(r.out << r.err);
  REQUIRE(r.exit_code == 0);
  int seen = 0;
  for (const StimulusEntry& e : read_manifest((out / "manifest.csv").string()).entries) {
    if (e.factors.at("method") != "ours") continue;
    ++seen;
    INFO(name << ": seam step ratio " << e.check.seam_step_ratio << ", stance-foot drift p99 "
              << e.quality.stance_foot_drift_p99_m << " m, flips " << e.quality.joint_flips);
    CHECK(e.check.seam_step_ratio > 0.0);
    CHECK(e.check.seam_step_ratio <= 1.5);
    CHECK(e.quality.stance_foot_drift_p99_m >= 0.0);
    CHECK(e.quality.stance_foot_drift_p99_m <= 0.010);
    CHECK(e.quality.joint_flips == 0);
  }
  CHECK(seen == 1);
}

}  // namespace test_loop_seam
