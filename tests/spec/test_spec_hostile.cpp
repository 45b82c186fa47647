// Bad specs found by fuzzing (issue 21): work estimated and refused before anything is enumerated,
// control characters in `name`, and text that is not one UTF-8 YAML document.
#include <catch2/catch.hpp>
#include <chrono>
#include <filesystem>
#include <fstream>

#include "framework/spec/load_experiment_spec.hpp"
#include "tests/support/run_cli.hpp"
#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_spec_hostile {

using namespace crowdlab;

namespace {

std::string errors_of(const std::string& text) {
  try {
    load_experiment_spec_text(text, "t.yaml", ".");
  } catch (const SpecError& e) {
    std::string all;
    for (const std::string& m : e.messages()) all += m + "\n";
    return all;
  }
  return "";
}

const std::string kHeader = "crowdlab: 1\nname: t\nseed: 5\n";
const std::string kLikert =
    "protocol:\n  type: likert\n  scale: {points: 6, labels: [a, b]}\n  questions: [{id: Q1, text: x}]\n"
    "outputs: {video: false, contact_sheet: false}\n";

std::string levels(int n, double first) {
  std::string s = "[";
  for (int i = 0; i < n; ++i) s += (i ? ", " : "") + std::to_string(first + 0.01 * i);
  return s + "]";
}

}  // namespace

TEST_CASE("spec: factor levels that multiply out to millions of conditions are refused at once") {
  // 40 x 40 x 3 x 2 x 1000 repetitions = 9.6 million conditions (validate used 7 GB and 20 s on this).
  const std::string text = kHeader + "scenario: {type: stationary, area: {width_m: 3, depth_m: 3}}\n" +
                           "factors:\n  density: " + levels(40, 1.0) + "\n  distance: " + levels(40, 0.2) +
                           "\n  trigger: [0, 50, 100]\n  method: [baseline, ours]\nrepetitions: 1000\n" +
                           kLikert;
  const auto start = std::chrono::steady_clock::now();
  const std::string errors = errors_of(text);
  CHECK(std::chrono::steady_clock::now() - start < std::chrono::seconds(2));
  CHECK_THAT(errors, Catch::Contains("t.yaml:") && Catch::Contains("factors") &&
                         Catch::Contains("9600000 conditions") && Catch::Contains("limit of 10000"));
}

TEST_CASE("spec: a crowd or a clip beyond the work limits is refused with the estimate") {
  // density 10 on 1000 x 1000 m: ten million characters (the crowd stage hung on this).
  std::string errors =
      errors_of(kHeader + "scenario: {type: stationary, area: {width_m: 1000, depth_m: 1000}}\n" +
                "factors:\n  density: [9.9]\n" + kLikert);
  CHECK_THAT(errors, Catch::Contains("t.yaml:") && Catch::Contains("9900000 characters") &&
                         Catch::Contains("limit of 10000"));
  // 3600 s at 240 fps with 20 characters: 17 million character-frames (7.2 GB when run).
  errors = errors_of(kHeader + "scenario: {type: stationary, area: {width_m: 2, depth_m: 2}}\n" +
                     "factors:\n  density: [5]\nduration_s: 3600\nfps: 240\n" + kLikert);
  CHECK_THAT(errors, Catch::Contains("t.yaml:") && Catch::Contains("duration_s") &&
                         Catch::Contains("17280000 character-frames") && Catch::Contains("limit of 2000000"));
  // The papers' specs stay well inside the limits.
  for (const char* spec : {"gomez2024_stationary", "gomez2024_nonstationary", "hoyet2016_crowds",
                           "hoyet2016_pairs", "demo", "manifold_demo"}) {
    INFO(spec);
    CHECK_NOTHROW(
        load_experiment_spec((test::source_dir() / "experiments" / (std::string(spec) + ".yaml")).string()));
  }
}

TEST_CASE("bench crowd refuses an agent count beyond its limit with exit 2") {
  const test::CliResult r = test::run_cli({"bench", "crowd", "--agents", "1000000000", "--steps", "1"});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains("--agents") && Catch::Contains("100000"));
}

TEST_CASE("spec: UTF-16, invalid UTF-8, several documents and control characters are refused") {
  const std::string valid = kHeader + "factors:\n  density: [2]\n" + kLikert;
  CHECK(errors_of(valid).empty());
  // UTF-16 LE with its byte-order mark, as some Windows editors save.
  std::string utf16 = "\xFF\xFE";
  for (char c : valid) utf16 += std::string(1, c) + '\0';
  CHECK_THAT(errors_of(utf16), Catch::Contains("t.yaml:1:1:") && Catch::Contains("UTF-16"));
  CHECK_THAT(errors_of(utf16.substr(2)), Catch::Contains("t.yaml:1:2:") && Catch::Contains("NUL byte"));
  // Latin-1 "é" in the name (line 2, column 8).
  std::string latin1 = valid;
  latin1.replace(latin1.find("name: t"), 7, "name: t\xE9");
  CHECK_THAT(errors_of(latin1), Catch::Contains("t.yaml:2:8:") && Catch::Contains("0xE9 is not valid UTF-8"));
  // Well-formed UTF-8 (and a UTF-8 byte-order mark) is fine.
  std::string utf8 = valid;
  utf8.replace(utf8.find("name: t"), 7, "name: t\xC3\xA9\xE2\x82\xAC");
  CHECK(errors_of(utf8).empty());
  CHECK(errors_of("\xEF\xBB\xBF" + valid).empty());
  // Only the first of several documents was used, silently.
  CHECK_THAT(errors_of(valid + "---\nname: second\n"),
             Catch::Contains("t.yaml:11:1:") && Catch::Contains("second YAML document"));
  CHECK(errors_of("---\n" + valid).empty());  // a leading marker is one document
  // ESC (ANSI colour codes) or a newline in the name.
  std::string ansi = valid;
  ansi.replace(ansi.find("name: t"), 7, "name: \"a\\e[2Jb\"");
  CHECK_THAT(errors_of(ansi),
             Catch::Contains("name") && Catch::Contains("control character (0x1b at byte 1)"));
}

TEST_CASE("spec: lists nested thousands deep are refused with the line and the limit, not 'bad file'") {
  const std::string header = kHeader + "factors:\n  density: [2]\n" + kLikert;
  // Flow style, on line 13 after a comment that holds brackets and a quoted value that holds them too:
  // yaml-cpp's own position for this is the end of the nest.
  const std::string flow =
      header + "# [[[ not a list\ndescription: '[[ {{'\nscenario: {extras: " + std::string(100000, '[') +
      std::string(100000, ']') + "}\n";
  std::string errors = errors_of(flow);
  CHECK_THAT(errors, Catch::Contains("t.yaml:13:11") && Catch::Contains("nesting too deep") &&
                         Catch::Contains("more than 500 levels"));
  CHECK_THAT(errors, !Catch::Contains("bad file"));
  // Block style: a line of 2,000 "- " opens 2,000 nested lists.
  std::string dashes = header + "description:\n";
  for (int i = 0; i < 2000; ++i) dashes += "- ";
  errors = errors_of(dashes + "x\n");
  CHECK_THAT(errors, Catch::Contains("t.yaml:12:") && Catch::Contains("nesting too deep"));
  // Through the CLI: exit 2 with the file named.
  const auto dir = test::scratch_dir("spec_deep_yaml");
  const auto path = dir / "deep.yaml";
  std::ofstream(path) << flow;
  const test::CliResult r = test::run_cli({"validate", path.string()});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains(path.string() + ":13:11") && Catch::Contains("nesting too deep"));
}

namespace {

std::string repeated(const std::string& level, int n) {
  std::string s = "[";
  for (int i = 0; i < n; ++i) s += (i ? ", " : "") + level;
  return s + "]";
}

size_t count_of(const std::string& text, const std::string& word) {
  size_t n = 0;
  for (size_t at = text.find(word); at != std::string::npos; at = text.find(word, at + 1)) ++n;
  return n;
}

}  // namespace

TEST_CASE("spec: duplicate levels are one error each, with file:line:col (issue 32)") {
  // V4 listed 5,000 times made one error per earlier copy: 12.5 million messages, 6.5 GB in validate.
  const std::string scenario = "scenario: {type: stationary, area: {width_m: 3, depth_m: 3}}\n";
  std::string errors = errors_of(kHeader + scenario + "factors:\n  viewpoint: " + repeated("V4", 2000) +
                                 "\n  density: [2]\n" + kLikert);
  CHECK(count_of(errors, "duplicate level") == 1999);
  CHECK_THAT(errors,
             Catch::Contains("t.yaml:6:") && Catch::Contains("factors.viewpoint[1]: duplicate level 'V4'"));
  // The same in protocol.practice (5.8 GB).
  const std::string practice_likert =
      "protocol:\n  type: likert\n  scale: {points: 6, labels: [a, b]}\n  questions: [{id: Q1, text: x}]\n"
      "  practice: {viewpoint: " +
      repeated("V1", 1000) + "}\noutputs: {video: false, contact_sheet: false}\n";
  errors =
      errors_of(kHeader + scenario + "factors:\n  viewpoint: [V1, V4]\n  density: [2]\n" + practice_likert);
  CHECK(count_of(errors, "duplicate level") == 999);
  CHECK_THAT(errors, Catch::Contains("protocol.practice.viewpoint[1]"));
}

TEST_CASE("spec: a factor longer than the level limit is refused from its length") {
  std::string many = "[";
  for (int i = 0; i < 10001; ++i)
    many += (i ? ", " : "") + std::to_string(1 + i % 9) + "." + std::to_string(i);
  many += "]";
  const std::string errors = errors_of(
      kHeader + "scenario: {type: stationary, area: {width_m: 3, depth_m: 3}}\nfactors:\n  density: " + many +
      "\n" + kLikert);
  CHECK_THAT(errors, Catch::Contains("factors.density") && Catch::Contains("10001 levels") &&
                         Catch::Contains("limit of 10000"));
  CHECK(count_of(errors, "\n") == 1);  // one message, no per-level errors
}

TEST_CASE("spec: practice conditions count toward the condition limit (issue 32)") {
  // Practice levels crossed with the blocks: 100 x 100 practice conditions over 2 x 2 test conditions
  // (plan went on to 1e7 with more levels).
  std::string densities = "[", distances = "[";
  for (int i = 0; i < 100; ++i) {
    densities += (i ? ", " : "") + std::to_string(1.0 + 0.01 * i);
    distances += (i ? ", " : "") + std::to_string(0.2 + 0.001 * i);
  }
  densities += "]";
  distances += "]";
  const std::string text = kHeader + "scenario: {type: stationary, area: {width_m: 3, depth_m: 3}}\n" +
                           "factors:\n  density: [1.0, 2.0]\n  distance: [0.2, 0.3]\n" +
                           "protocol:\n  type: likert\n  scale: {points: 6, labels: [a, b]}\n"
                           "  questions: [{id: Q1, text: x}]\n  practice: {density: " +
                           densities + ", distance: " + distances +
                           "}\noutputs: {video: false, contact_sheet: false}\n";
  const std::string errors = errors_of(text);
  CHECK_THAT(errors, Catch::Contains("protocol.practice") && Catch::Contains("10000 practice conditions") &&
                         Catch::Contains("10004") && Catch::Contains("limit of 10000"));
}

TEST_CASE("spec: a manifold mesh that run would refuse is refused at its line and column") {
  // Issue 33: `mesh: bogus_scene` and `mesh: /etc/passwd` passed validate; run refused them without a line.
  const std::string base = kHeader + kLikert + "factors: {method: [baseline]}\n";
  const std::string bogus = errors_of(base + "scenario: {type: manifold, mesh: bogus_scene}\n");
  CHECK_THAT(bogus, Catch::Contains("t.yaml:") && Catch::Contains("scenario.mesh: unknown surface scene "
                                                                  "'bogus_scene' (expected one of building"));
  const std::string passwd = errors_of(base + "scenario: {type: manifold, mesh: /etc/passwd}\n");
  CHECK_THAT(passwd,
             Catch::Contains("scenario.mesh: '/etc/passwd' is not a mesh file (.obj, .gltf or .glb)"));
  CHECK(errors_of(base + "scenario: {type: manifold, mesh: floor_wall}\n").find("scenario.mesh") ==
        std::string::npos);
}

TEST_CASE("spec: flow crowds are counted from their lattice and refused past the character limits") {
  // Issue 33: a flow-B corridor of density 10 on 1000 m (5 GB at 180 s), spacing 0.01 m, and an hour at
  // 240 fps all passed validate (a flow's crowd size was not estimated).
  const std::string area = "scenario: {type: flow_b, area: {width_m: 1000, depth_m: 1000}";
  const std::string dense = errors_of(kHeader + kLikert + area + "}\nfactors: {density: [10]}\n");
  CHECK_THAT(dense, Catch::Contains("the largest crowd has 9998244 characters") &&
                        Catch::Contains("more than the limit of 10000"));
  const std::string spaced =
      errors_of(kHeader + kLikert + area + ", initial_spacing_m: 0.01}\nfactors: {method: [baseline]}\n");
  CHECK_THAT(spaced, Catch::Contains("the largest crowd has 1e+10 characters"));
  const std::string hour = errors_of(kHeader + kLikert +
                                     "scenario: {type: flow_b, area: {width_m: 10, depth_m: 10}}\n"
                                     "factors: {density: [1]}\nduration_s: 3600\nfps: 240\n");
  CHECK_THAT(hour, Catch::Contains("100 characters x 864000 frames"));
  CHECK(errors_of(kHeader + kLikert +
                  "scenario: {type: flow_b, area: {width_m: 10, depth_m: 10}}\n"
                  "factors: {density: [1]}\n")
            .empty());
}

TEST_CASE("validate refuses a crowd without a size, naming scenario.agents, as run does") {
  // Issue 30: a stationary spec with no `characters` or `density` factor and no scenario.agents passed
  // validate and was refused minutes later by run.
  const std::filesystem::path dir = test::scratch_dir("validate_crowd_size");
  const std::string body = kHeader + kLikert + "factors: {method: [baseline, ours]}\n";
  const std::filesystem::path unsized = dir / "unsized.yaml";
  std::ofstream(unsized) << body << "scenario: {type: stationary}\n";
  const test::CliResult r = test::run_cli({"validate", unsized.string()});
  CHECK(r.exit_code == 2);
  CHECK_THAT(r.err, Catch::Contains("unsized.yaml:") && Catch::Contains("scenario.agents") &&
                        Catch::Contains("the crowd size is unknown"));
  const std::filesystem::path sized = dir / "sized.yaml";
  std::ofstream(sized) << body << "scenario: {type: stationary, agents: 12}\n";
  CHECK(test::run_cli({"validate", sized.string()}).exit_code == 0);
}

}  // namespace test_spec_hostile
