// CSV table, manifest round trip and SHA-256 known answers.
#include <catch2/catch.hpp>
#include <fstream>

#include "framework/core/csv.hpp"
#include "framework/core/error.hpp"
#include "framework/core/sha256.hpp"
#include "framework/core/stimulus_manifest.hpp"
#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_csv {

using namespace crowdlab;

TEST_CASE("csv parses quotes, commas and newlines, and round-trips through csv_line") {
  const std::vector<std::string> fields = {"a,b", "say \"hi\"", "two\nlines", "plain", ""};
  const CsvTable t = parse_csv(csv_line({"c1", "c2", "c3", "c4", "c5"}) + csv_line(fields), "mem");
  REQUIRE(t.rows.size() == 1);
  CHECK(t.rows[0] == fields);
}

TEST_CASE("csv errors name file, line and column") {
  CHECK_THROWS_WITH(parse_csv("a,b\n1,2\n3\n", "x.csv"), Catch::Contains("x.csv:3"));
  const CsvTable t = parse_csv("a,b\n1,2\n3,oops\n", "y.csv");
  CHECK(t.number(0, 1) == 2.0);
  CHECK_THROWS_WITH(t.number(1, 1), Catch::Contains("y.csv:3:2") && Catch::Contains("column 'b'"));
  CHECK_THROWS_WITH(t.column("zzz"), Catch::Contains("missing column 'zzz'"));
  CHECK_THROWS_AS(parse_csv("a\n\"open\n", "z.csv"), InputError);
}

TEST_CASE("csv: a UTF-8 byte-order mark is not part of the first column's name (issue 21)") {
  // Excel's "CSV UTF-8" starts with EF BB BF; the first column was then "\xEF\xBB\xBFsubject".
  const CsvTable t = parse_csv("\xEF\xBB\xBFsubject,y\n1,2\n", "bom.csv");
  CHECK(t.column("subject") == 0);
  CHECK(t.number(0, 1) == 2.0);
}

TEST_CASE("sha256 known answers") {
  CHECK(sha256_hex("") == "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  CHECK(sha256_hex("abc") == "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  CHECK(sha256_hex(std::string(1000, 'a')) ==
        "41edece42d63e8d9bf515a9ba6932e1c20cbc9f5a5d134645adb5db1b9737ea3");
}

TEST_CASE("stimulus manifest round-trips") {
  StimulusManifest m;
  m.factor_names = {"density", "viewpoint"};
  StimulusEntry e;
  e.id = "density-2.22_viewpoint-V1";
  e.factors = {{"density", "2.22"}, {"viewpoint", "V1"}};
  e.file = "density-2.22_viewpoint-V1/V1.mp4";
  e.duration_s = 20;
  e.frames = 600;
  e.width = 1920;
  e.height = 1080;
  e.sha256 = "ab";
  e.mean_overlap_l = 0.25;
  m.entries = {e};
  const auto dir = test::scratch_dir("manifest");
  write_manifest(m, (dir / "manifest.csv").string());
  const StimulusManifest back = read_manifest((dir / "manifest.csv").string());
  REQUIRE(back.entries.size() == 1);
  CHECK(back.factor_names == m.factor_names);
  CHECK(back.entries[0].factors == e.factors);
  CHECK(back.entries[0].mean_overlap_l == 0.25);
  CHECK(back.entries[0].v_i_m == -1.0);
  CHECK(back.entries[0].frames == 600);
  CHECK(back.entries[0].quality.depth_p99_m == -1.0);
  CHECK(back.entries[0].quality.foot_pops == -1);
}

TEST_CASE("stimulus manifest carries the clip's correction-quality columns") {
  StimulusManifest m;
  StimulusEntry e;
  e.id = "c1";
  e.file = "c1.mp4";
  e.quality.depth_p99_m = 0.0042;
  e.quality.depth_max_m = 0.02;
  e.quality.stance_foot_drift_p99_m = 0.0008;
  e.quality.stance_foot_drift_max_m = 0.0012;
  e.quality.foot_pops = 3;
  e.quality.foot_ground_penetration_max_m = 0.0;
  e.quality.foot_ground_penetration_added_max_m = 0.0035;
  e.quality.foot_float_p99_m = 0.005;
  e.quality.free_limb_dev_p99_deg = 0.4;
  e.quality.free_limb_dev_max_deg = 2.5;
  e.quality.joint_flips = 7;
  e.quality.env_penetration_p99_m = 0.003;
  e.quality.env_penetration_max_m = 0.011;
  e.quality.mesh_overlap_fraction = 0.0125;
  e.quality.mesh_overlap_depth_p99_m = 0.006;
  e.quality.proxy_coverage = 0.93;
  e.quality.proxy_outside_p99_m = 0.021;
  m.entries = {e};
  const auto dir = test::scratch_dir("manifest_quality");
  const std::string path = (dir / "manifest.csv").string();
  write_manifest(m, path);
  const std::string header = test::slurp(path).substr(0, test::slurp(path).find('\n'));
  CHECK(header.ends_with(
      ",practice,depth_p99_m,depth_max_m,stance_foot_drift_p99_m,stance_foot_drift_max_m,"
      "foot_pops,foot_ground_penetration_max_m,foot_ground_penetration_added_max_m,foot_float_p99_m,"
      "free_limb_dev_p99_deg,free_limb_dev_max_deg,joint_flips,env_penetration_p99_m,env_penetration_max_m,"
      "mesh_overlap_fraction,mesh_overlap_depth_p99_m,proxy_coverage,proxy_outside_p99_m,"
      "crowd_in_frame_min,character_height_px,overlap_frame_share,overlap_pixel_fraction,"
      "seam_step_ratio"));
  const ClipQuality q = read_manifest(path).entries.at(0).quality;
  CHECK(q.depth_p99_m == 0.0042);
  CHECK(q.depth_max_m == 0.02);
  CHECK(q.stance_foot_drift_p99_m == 0.0008);
  CHECK(q.stance_foot_drift_max_m == 0.0012);
  CHECK(q.foot_pops == 3);
  CHECK(q.foot_ground_penetration_max_m == 0.0);
  CHECK(q.foot_ground_penetration_added_max_m == 0.0035);
  CHECK(q.foot_float_p99_m == 0.005);
  CHECK(q.free_limb_dev_p99_deg == 0.4);
  CHECK(q.free_limb_dev_max_deg == 2.5);
  CHECK(q.joint_flips == 7);
  CHECK(q.env_penetration_p99_m == 0.003);
  CHECK(q.env_penetration_max_m == 0.011);
  CHECK(q.mesh_overlap_fraction == 0.0125);
  CHECK(q.mesh_overlap_depth_p99_m == 0.006);
  CHECK(q.proxy_coverage == 0.93);
  CHECK(q.proxy_outside_p99_m == 0.021);
  // A manifest written before these columns existed still reads, with the measures unknown.
  std::ofstream(path, std::ios::trunc)
      << "id,file,duration_s,frames,width,height,sha256,overlap_l,v_i_m,collisions,practice\n"
         "c1,c1.mp4,1,30,64,48,ab,0.1,,,0\n";
  const StimulusEntry old = read_manifest(path).entries.at(0);
  CHECK(old.mean_overlap_l == 0.1);
  CHECK(old.quality.foot_pops == -1);
  CHECK(old.quality.foot_float_p99_m == -1.0);
  CHECK(old.quality.joint_flips == -1);
  CHECK(old.quality.free_limb_dev_max_deg == -1.0);
}

TEST_CASE("stimulus manifest carries the clip's stimulus-check columns") {
  StimulusManifest m;
  StimulusEntry e;
  e.id = "c1";
  e.file = "c1.mp4";
  e.check.crowd_in_frame_min = 0.975;
  e.check.character_height_px = 212.5;
  e.check.overlap_frame_share = 0.5;
  e.check.overlap_pixel_fraction = 0.0031;
  e.check.seam_step_ratio = 1.25;
  m.entries = {e};
  const auto dir = test::scratch_dir("manifest_check");
  const std::string path = (dir / "manifest.csv").string();
  write_manifest(m, path);
  const StimulusCheck c = read_manifest(path).entries.at(0).check;
  CHECK(c.crowd_in_frame_min == 0.975);
  CHECK(c.character_height_px == 212.5);
  CHECK(c.overlap_frame_share == 0.5);
  CHECK(c.overlap_pixel_fraction == 0.0031);
  CHECK(c.seam_step_ratio == 1.25);
  // A manifest without the columns reads with the check unknown.
  std::ofstream(path, std::ios::trunc)
      << "id,file,duration_s,frames,width,height,sha256,overlap_l,v_i_m,collisions,practice\n"
      << "c1,c1.mp4,1,30,64,48,x,,,,0\n";
  CHECK(read_manifest(path).entries.at(0).check.seam_step_ratio == -1.0);
}

}  // namespace test_csv
