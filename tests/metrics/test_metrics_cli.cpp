// `crowdlab metrics CROWD.glb --json` on a crowd written by write_crowd_glb agrees with the library.
#include <catch2/catch.hpp>
#include <fstream>
#include <nlohmann/json.hpp>

#include "framework/io/read_crowd_glb.hpp"
#include "framework/io/write_crowd_glb.hpp"
#include "framework/metrics/correction_quality.hpp"
#include "framework/metrics/measure_crowd.hpp"
#include "tests/support/run_cli.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_metrics_cli {

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

TEST_CASE("crowdlab metrics --input adds the correction-quality measures against the input") {
  // The "corrected" crowd is the input with the standing character's feet jumping 8 cm on frame 3 (the
  // whole body moved), so the library's foot pops and drift are known and nonzero.
  const auto dir = test::scratch_dir("metrics-cli-input");
  const std::string in_path = (dir / "in.glb").string(), out_path = (dir / "out.glb").string();
  const CrowdAnimation in = approaching_pair();
  CrowdAnimation out = in;
  for (size_t f = 3; f < out.characters[0].frames.size(); ++f)
    out.characters[0].frames[f].root_position_m.z() += 0.08;
  // The other character sunk 3 cm from frame 3 on (less than a pop): feet below the input's ground.
  for (size_t f = 3; f < out.characters[1].frames.size(); ++f)
    out.characters[1].frames[f].root_position_m.y() -= 0.03;
  write_crowd_glb(in, in_path);
  write_crowd_glb(out, out_path);
  const CorrectionQuality expected =
      measure_correction_quality(read_crowd_glb(in_path), read_crowd_glb(out_path));
  REQUIRE(expected.feet.foot_pops == 4);  // four foot joints of the standing character, once
  const test::CliResult r = test::run_cli({"-q", "metrics", out_path, "--input", in_path, "--json"});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  const nlohmann::json q = nlohmann::json::parse(r.out).at("correction_quality");
  CHECK(q.at("foot_pops").get<int>() == expected.feet.foot_pops);
  CHECK(q.at("stance_foot_drift_max_m").get<double>() == Approx(expected.feet.stance_drift_max_m));
  CHECK(q.at("stance_foot_drift_p99_m").get<double>() == Approx(expected.feet.stance_drift_p99_m));
  CHECK(q.at("depth_p99_m").get<double>() == Approx(expected.depth_p99_m));
  CHECK(q.at("foot_ground_penetration_max_m").get<double>() ==
        Approx(expected.feet.ground_penetration_max_m));
  REQUIRE(expected.feet.ground_penetration_added_max_m > 0.02);
  CHECK(q.at("foot_ground_penetration_added_max_m").get<double>() ==
        Approx(expected.feet.ground_penetration_added_max_m));
  CHECK(q.at("foot_ground_penetration_added_p99_m").get<double>() ==
        Approx(expected.feet.ground_penetration_added_p99_m));
  const test::CliResult text = test::run_cli({"-q", "metrics", out_path, "--input", in_path});
  CHECK(text.exit_code == 0);
  CHECK(text.out.find("foot pops 4") != std::string::npos);
  CHECK(text.out.find("added by the correction") != std::string::npos);
  // The flip threshold printed is the clip's own (200 deg/s over 0.1 s; core/joint_flips.hpp): 20 deg
  // within 3 frames at 30 fps, 26.7 deg within 2 at 15 fps.
  CHECK(text.out.find("> 20.0 deg within 3 frames") != std::string::npos);
  CrowdAnimation in15 = in, out15 = out;
  in15.meta.fps = out15.meta.fps = 15.0;
  const std::string in15_path = (dir / "in15.glb").string(), out15_path = (dir / "out15.glb").string();
  write_crowd_glb(in15, in15_path);
  write_crowd_glb(out15, out15_path);
  const test::CliResult text15 = test::run_cli({"-q", "metrics", out15_path, "--input", in15_path});
  INFO(text15.out << text15.err);
  CHECK(text15.out.find("> 26.7 deg within 2 frames") != std::string::npos);
  // An input that does not match the crowd is bad input (exit code 2).
  CrowdAnimation shorter = in;
  for (auto& c : shorter.characters) c.frames.pop_back();
  const std::string short_path = (dir / "short.glb").string();
  write_crowd_glb(shorter, short_path);
  CHECK(test::run_cli({"-q", "metrics", out_path, "--input", short_path}).exit_code == 2);
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

}  // namespace test_metrics_cli
