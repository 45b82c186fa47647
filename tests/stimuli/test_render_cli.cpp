// `crowdlab render` end to end: a crowd file in, an MP4 (and overlap CSV) out; bad input exits 2.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "framework/io/write_crowd_glb.hpp"
#include "stimuli/synthetic_crowd.hpp"
#include "tests/support/run_cli.hpp"
#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_render_cli {

using namespace crowdlab;

TEST_CASE(
    "crowdlab render: glb -> mp4 with the overlap CSV, and exit 2 for odd sizes, unknown viewpoints, missing "
    "files",
    "[stimuli][cli]") {
  const auto dir = test::scratch_dir("render_cli");
  stimuli::SyntheticCrowdOptions co;
  co.characters = 3;
  co.frames = 6;
  co.spacing_m = 0.4;
  const std::string glb = (dir / "crowd.glb").string();
  write_crowd_glb(stimuli::make_synthetic_crowd(co), glb);
  const std::string mp4 = (dir / "clip.mp4").string();
  const auto ok = test::run_cli({"-q", "render", glb, "--viewpoint", "V2", "--out", mp4, "--width", "160",
                                 "--height", "96", "--overlap"});
  INFO(ok.err);
  REQUIRE(ok.exit_code == 0);
  CHECK(std::filesystem::file_size(mp4) > 100);
  std::ifstream csv(mp4 + ".overlap.csv");
  std::string line;
  int rows = -1;
  while (std::getline(csv, line)) ++rows;
  CHECK(rows == 6);

  const auto odd = test::run_cli(
      {"-q", "render", glb, "--out", (dir / "odd.mp4").string(), "--width", "161", "--height", "96"});
  CHECK(odd.exit_code == 2);
  CHECK(odd.err.find("even") != std::string::npos);
  const auto unknown = test::run_cli({"-q", "render", glb, "--viewpoint", "V7", "--out",
                                      (dir / "u.mp4").string(), "--width", "160", "--height", "96"});
  CHECK(unknown.exit_code == 2);
  CHECK(unknown.err.find("V7") != std::string::npos);
  const auto missing =
      test::run_cli({"-q", "render", (dir / "nope.glb").string(), "--out", (dir / "m.mp4").string()});
  CHECK(missing.exit_code == 2);
  // An unknown x264 preset is bad input (exit 2, named), not an encoder failure (exit 1; issue 21).
  const auto preset = test::run_cli({"-q", "render", glb, "--out", (dir / "p.mp4").string(), "--width", "160",
                                     "--height", "96", "--preset", "bogus"});
  CHECK(preset.exit_code == 2);
  CHECK(preset.err.find("unknown x264 preset 'bogus'") != std::string::npos);
}

}  // namespace test_render_cli
