// `crowdlab metrics CROWD.glb --json` on a crowd written by write_crowd_glb agrees with the library.
#include <catch2/catch.hpp>
#include <fstream>
#include <nlohmann/json.hpp>

#include "framework/io/read_crowd_glb.hpp"
#include "framework/io/write_crowd_glb.hpp"
#include "framework/metrics/measure_crowd.hpp"
#include "tests/support/run_cli.hpp"

using namespace crowdlab;

namespace {

CrowdAnimation approaching_pair() {
  CrowdAnimation crowd;
  crowd.meta.fps = 30.0;
  crowd.meta.condition_id = "metrics-cli";
  for (int c = 0; c < 2; ++c) {
    CharacterAnimation ch;
    ch.name = "c00" + std::to_string(c);
    ch.shape = make_procedural_body({c == 0 ? Sex::kMale : Sex::kFemale, c == 0 ? 1.8 : 1.62, 1.0});
    for (double x : {2.5, 2.0, 0.5, 0.35, 2.2, 0.4}) {
      Pose p = Pose::rest(ch.shape);
      p.root_position_m = Vec3(c == 0 ? 0.0 : x, ch.shape.pelvis_height_m(), 0.0);
      p.local_rotations[kPelvis] = Quat(Eigen::AngleAxisd(c == 0 ? 0.0 : 3.0, Vec3::UnitY()));
      ch.frames.push_back(p);
    }
    crowd.characters.push_back(ch);
  }
  return crowd;
}

}  // namespace

TEST_CASE("crowdlab metrics prints the library's measures as JSON") {
  const auto dir = test::scratch_dir("metrics-cli");
  const std::string path = (dir / "pair.glb").string();
  write_crowd_glb(approaching_pair(), path);
  const CrowdMetrics expected = measure_crowd(read_crowd_glb(path));
  const test::CliResult r = test::run_cli({"-q", "metrics", path, "--json", "--per-frame"});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const nlohmann::json j = nlohmann::json::parse(r.out);
  CHECK(j.at("characters").get<int>() == 2);
  CHECK(j.at("frames").get<int>() == 6);
  CHECK(j.at("collision_count").get<int>() == expected.collision_count);
  CHECK(expected.collision_count == 2);
  CHECK(j.at("mean_character_overlap_l").get<double>() == Approx(expected.mean_character_overlap_l));
  CHECK(j.at("volume_index_m").get<double>() == Approx(expected.volume_index_m));
  CHECK(j.at("max_penetration_depth_m").get<double>() == Approx(expected.max_penetration_depth_m));
  CHECK(j.at("per_frame").at("colliding_pairs").size() == 6);
  CHECK(j.at("pairs").size() == 1);
  const test::CliResult text = test::run_cli({"-q", "metrics", path});
  CHECK(text.exit_code == 0);
  CHECK(text.out.find("mean per-character overlap") != std::string::npos);
}

TEST_CASE("crowdlab metrics rejects a missing or corrupt file with exit code 2") {
  const auto dir = test::scratch_dir("metrics-cli-bad");
  CHECK(test::run_cli({"metrics", (dir / "missing.glb").string()}).exit_code == 2);
  {
    std::ofstream out(dir / "bad.glb", std::ios::binary);
    out << "glTF not really";
  }
  const test::CliResult r = test::run_cli({"metrics", (dir / "bad.glb").string()});
  CHECK(r.exit_code == 2);
  CHECK(r.err.find("bad.glb") != std::string::npos);
}
