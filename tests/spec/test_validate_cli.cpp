// `crowdlab validate` on the shipped specs and on broken ones, through the real binary.
#include <catch2/catch.hpp>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "tests/support/run_cli.hpp"
#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_validate_cli {

using namespace crowdlab;
using test::run_cli;

namespace {

std::string spec_path(const std::string& name) {
  return (test::source_dir() / "experiments" / name).string();
}

std::string write_spec(const std::string& dir_name, const std::string& text) {
  const auto dir = test::scratch_dir(dir_name);
  const auto path = dir / "spec.yaml";
  std::ofstream(path) << text;
  return path.string();
}

// A minimal valid spec; tests append or replace lines to break it in one known place.
const char* kValidSpec =
    "crowdlab: 1\n"              // line 1
    "name: cli_test\n"           // line 2
    "seed: 42\n"                 // line 3
    "factors:\n"                 // line 4
    "  density: [2.22, 4.44]\n"  // line 5
    "  method: [baseline, ours]\n"
    "repetitions: 2\n"  // line 7
    "fps: 30\n"         // line 8
    "protocol:\n"
    "  type: likert\n"
    "  questions:\n"
    "    - {id: Q1, text: \"Natural?\"}\n";

int count_table_rows(const std::string& out, const std::string& prefix) {
  int rows = 0;
  std::istringstream in(out);
  for (std::string line; std::getline(in, line);)
    if (line.rfind(prefix, 0) == 0) ++rows;
  return rows;
}

}  // namespace

TEST_CASE("validate prints 40 conditions for gomez2024_stationary, with a table row for each") {
  const auto r = run_cli({"validate", spec_path("gomez2024_stationary.yaml")});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.out, Catch::Contains("\n40 conditions\n"));
  CHECK(count_table_rows(r.out, "density-") == 40);
  CHECK_THAT(r.out, Catch::Contains("density-6.66_viewpoint-V4_method-ours_rep-1"));
  CHECK_THAT(r.out, Catch::Contains("(reverse-keyed)"));
}

TEST_CASE("validate prints 264 conditions plus 6 practice trials for hoyet2016_pairs") {
  const auto r = run_cli({"validate", spec_path("hoyet2016_pairs.yaml")});
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  CHECK_THAT(r.out, Catch::Contains("\n264 conditions (+6 practice)\n"));
  CHECK(count_table_rows(r.out, "shoulder-") == 264);
  CHECK(count_table_rows(r.out, "practice_shoulder-") == 6);
}

TEST_CASE("validate counts the other shipped specs") {
  const std::vector<std::pair<std::string, std::string>> expected = {
      {"gomez2024_nonstationary.yaml", "\n20 conditions\n"},
      {"hoyet2016_crowds.yaml", "\n120 conditions (+12 practice)\n"},
      {"demo.yaml", "\n8 conditions (+1 practice)\n"},  // instructions and one practice trial (issue 21)
  };
  for (const auto& [file, count] : expected) {
    const auto r = run_cli({"validate", spec_path(file), "--no-table"});
    INFO(file << "\n" << r.err);
    CHECK(r.exit_code == 0);
    CHECK_THAT(r.out, Catch::Contains(count));
  }
}

TEST_CASE("validate: a wrong type exits 2 and names file, line, column and key") {
  std::string text = kValidSpec;
  text.replace(text.find("fps: 30"), 7, "fps: fast");
  const std::string path = write_spec("validate-type", text);
  const auto r = run_cli({"validate", path});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains(path + ":8:6: fps: expected a number, got 'fast'"));
}

TEST_CASE("validate: an unknown key exits 2 with the exact line and a suggestion") {
  std::string text = kValidSpec;
  text.replace(text.find("repetitions: 2"), 14, "repetitons: 2");
  const std::string path = write_spec("validate-unknown", text);
  const auto r = run_cli({"validate", path});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains(path + ":7:1: repetitons: unknown key (did you mean 'repetitions'?)"));
}

TEST_CASE("validate: a missing file exits 2 with the exact line") {
  const std::string path = write_spec("validate-missing", std::string(kValidSpec) +
                                                              "animation:\n"
                                                              "  motion: clips\n"
                                                              "  dance_clips: [nowhere/dance.bvh]\n");
  const auto r = run_cli({"validate", path});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err,
             Catch::Contains(path + ":15:17: animation.dance_clips[0]: file not found: 'nowhere/dance.bvh'"));
}

TEST_CASE("validate reports every problem, one per line, in file order") {
  std::string text = kValidSpec;
  text.replace(text.find("fps: 30"), 7, "fps: -3");
  text.replace(text.find("[baseline, ours]"), 16, "[baseline, ourz]");
  text += "outputs: {video: sometimes}\n";
  const std::string path = write_spec("validate-many", text);
  const auto r = run_cli({"validate", path});
  CHECK(r.exit_code == 2);
  // Lines of the form "<path>:<line>:<column>: ..."; collect <line>.
  std::vector<int> lines;
  std::istringstream err(r.err);
  for (std::string l; std::getline(err, l);)
    if (l.rfind(path + ":", 0) == 0 && l.size() > path.size() + 1 &&
        std::isdigit(static_cast<unsigned char>(l[path.size() + 1])))
      lines.push_back(std::stoi(l.substr(path.size() + 1)));
  REQUIRE(lines.size() == 3);
  CHECK(lines == std::vector<int>{6, 8, 13});
  CHECK_THAT(r.err, Catch::Contains("3 problems found"));
}

TEST_CASE("validate: a missing spec file and a YAML syntax error exit 2") {
  auto r = run_cli({"validate", (test::scratch_dir("validate-nofile") / "absent.yaml").string()});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains("cannot open"));
  const std::string path = write_spec("validate-syntax", "name: x\nfactors: [a, b\n");
  r = run_cli({"validate", path});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains(path + ":"));
  CHECK_THAT(r.err, Catch::Contains("YAML syntax error"));
}

TEST_CASE("validate --help describes the command") {
  const auto r = run_cli({"validate", "--help"});
  CHECK(r.exit_code == 0);
  CHECK_THAT(r.out, Catch::Contains("condition table"));
  CHECK_THAT(r.out, Catch::Contains("--no-table"));
}

namespace {
// id -> seed from the condition table that `crowdlab validate` prints.
std::map<std::string, std::string> table_seeds(const std::string& out) {
  std::map<std::string, std::string> seeds;
  std::istringstream in(out);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("density-", 0) != 0) continue;
    std::istringstream cells(line);
    std::vector<std::string> words;
    for (std::string w; cells >> w;) words.push_back(w);
    seeds[words.front()] = words.back();
  }
  return seeds;
}
}  // namespace

TEST_CASE("validate: adding a level keeps every other id and seed, and output is deterministic") {
  std::string text = kValidSpec;
  const std::string before_path = write_spec("validate-before", text);
  text.replace(text.find("[2.22, 4.44]"), 12, "[2.22, 3.33, 4.44]");
  const std::string after_path = write_spec("validate-after", text);
  const auto before = run_cli({"validate", before_path});
  const auto again = run_cli({"validate", before_path});
  const auto after = run_cli({"validate", after_path});
  REQUIRE(before.exit_code == 0);
  REQUIRE(after.exit_code == 0);
  CHECK(before.out == again.out);
  const auto a = table_seeds(before.out);
  const auto b = table_seeds(after.out);
  CHECK(a.size() == 8);
  CHECK(b.size() == 12);
  for (const auto& [id, seed] : a) {
    INFO(id);
    REQUIRE(b.count(id) == 1);
    CHECK(b.at(id) == seed);
  }
}

TEST_CASE("validate reads the manifold mesh as run does: a bad file and a crowd too large for its area") {
  // Issue 33: validate passed a mesh run could not read, and a density of 0.1 on a 1 km OBJ (which
  // overflowed an int in run and was reported as "agents: must be >= 1").
  const auto dir = test::scratch_dir("validate-manifold");
  std::ofstream(dir / "km.obj")
      << "v -500 0 -500\nv 500 0 -500\nv 500 0 500\nv -500 0 500\nf 1 2 3\nf 1 3 4\n";
  std::ofstream(dir / "broken.obj") << "v 0 0 0\nv 1 0 0\nf 1 2 9\n";
  const auto spec = [&](const std::string& mesh, const std::string& factors) {
    const auto path = dir / ("spec_" + mesh + ".yaml");
    std::ofstream(path) << "crowdlab: 1\nname: m\nseed: 1\n"
                        << "scenario:\n  type: manifold\n  mesh: " << mesh << "\n"  // mesh: line 6
                        << "crowd: {model: orca}\nfactors:\n"
                        << factors << "  method: [baseline]\n"
                        << "protocol:\n  type: likert\n  questions:\n    - {id: Q1, text: \"Natural?\"}\n";
    return path.string();
  };
  const auto huge = run_cli({"validate", spec("km.obj", "  density: [0.001, 0.1]\n")});
  CHECK(huge.exit_code == 2);
  CHECK_THAT(huge.err,
             Catch::Contains("spec_km.obj.yaml:9:12: factors.density: the largest crowd on") &&
                 Catch::Contains("(1000000 m^2) has 100000 characters, more than the limit of 10000"));
  const auto small = run_cli({"validate", spec("km.obj", "  density: [0.001]\n")});
  INFO(small.err);
  CHECK(small.exit_code == 0);
  const auto broken = run_cli({"validate", spec("broken.obj", "  density: [1]\n")});
  CHECK(broken.exit_code == 2);
  CHECK_THAT(broken.err,
             Catch::Contains("spec_broken.obj.yaml:6:9: scenario.mesh: ") && Catch::Contains("broken.obj"));
}

TEST_CASE("validate reads the motion clips and characters a spec names, as run does") {
  // Issue 33 item 2: a dance clip or a glTF character that was not one passed validate (it only checked
  // that the file existed); run refused it later, without the spec's line.
  const auto dir = test::scratch_dir("validate-referenced");
  std::ofstream(dir / "bad.bvh") << "not a bvh\n";
  std::ofstream(dir / "bad.glb") << "junk";
  const std::string walk = (test::source_dir() / "tests/data/fuzz/walk.bvh").string();
  const auto write = [&](const std::string& name, const std::string& extra) {
    std::ofstream(dir / name) << kValidSpec << extra;
    return (dir / name).string();
  };
  // kValidSpec is 12 lines: "animation:" is line 13, its dance_clips line 15.
  const auto clip = run_cli({"validate", write("clip.yaml", "animation:\n  motion: clips\n  dance_clips: [" +
                                                                walk + ", bad.bvh]\n")});
  CHECK(clip.exit_code == 2);
  CHECK_THAT(clip.err, Catch::Contains("clip.yaml:15:") && Catch::Contains("animation.dance_clips[1]: ") &&
                           Catch::Contains("bad.bvh"));
  const auto good = run_cli(
      {"validate", write("good.yaml", "animation:\n  motion: clips\n  dance_clips: [" + walk + "]\n")});
  INFO(good.err);
  CHECK(good.exit_code == 0);
  const auto character = run_cli({"validate", write("character.yaml", "render:\n  characters: [bad.glb]\n")});
  CHECK(character.exit_code == 2);
  CHECK_THAT(character.err,
             Catch::Contains("character.yaml:14:16: render.characters[0]: ") && Catch::Contains("bad.glb"));
}

TEST_CASE("validate loads the MPFB2 asset folder a spec names, as run does") {
  // Issue 33 item 2: an asset folder without its files passed validate (it only had to be a folder); run
  // refused it in the animation stage.
  const auto dir = test::scratch_dir("validate-mpfb2");
  std::filesystem::create_directories(dir / "empty");
  std::ofstream(dir / "spec.yaml") << kValidSpec << "animation:\n  body_model: {type: mpfb2, path: empty}\n";
  const auto r = run_cli({"validate", (dir / "spec.yaml").string()});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains("spec.yaml:14:15: animation.body_model: ") &&
                        Catch::Contains("base.obj: cannot open OBJ file"));
}

}  // namespace test_validate_cli
