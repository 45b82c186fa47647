// The spec loader as a library: typed values, every error kind, stable ids and seeds, practice trials.
#include <catch2/catch.hpp>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>

#include "framework/core/seed.hpp"
#include "framework/core/sha256.hpp"
#include "framework/spec/did_you_mean.hpp"
#include "framework/spec/load_experiment_spec.hpp"
#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_spec_loader {

using namespace crowdlab;

namespace {

ExperimentSpec load_text(const std::string& text, const std::string& base = ".") {
  return load_experiment_spec_text(text, "t.yaml", base);
}

// All error messages for `text` (empty when it loads).
std::vector<std::string> errors_of(const std::string& text, const std::string& base = ".") {
  try {
    load_text(text, base);
  } catch (const SpecError& e) {
    return e.messages();
  }
  return {};
}

std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& m : v) s += m + "\n";
  return s;
}

using crowdlab::test::slurp;

// The named factor of a loaded spec. Throws (a test error) when the spec has none: the explicit throw also
// tells GCC the pointer is not null, which -Wnull-dereference needs at the tests' -O1 (issue 31).
const Factor& factor_of(const ExperimentSpec& spec, const std::string& name) {
  const Factor* factor = spec.factor(name);
  if (factor == nullptr) throw std::runtime_error("the spec has no factor '" + name + "'");
  return *factor;
}

const std::string kHeader = "crowdlab: 1\nname: t\nseed: 5\n";

}  // namespace

TEST_CASE("a spec's values reach the typed structs, with units and defaults") {
  const ExperimentSpec s = load_text(
      kHeader +
      "scenario: {type: corridor, area: {width_m: 2.5, depth_m: 8}}\n"
      "crowd: {model: social, agent_radius_m: 0.2, cost_weights: {goal: 1.5}}\n"
      "factors:\n  density: {levels: [2.22, 3.33]}\n  viewpoint: [V3]\n"
      "duration_s: 12.5\nfps: 25\nresolution: [1280, 720]\n"
      "render: {crf: 23, msaa: 4, background: '#102030', viewpoints: {V3: [1, 2, 3, 0, 1, 0, 50]}}\n"
      "protocol:\n  type: rating\n  scale: {points: 7, labels: [low, high]}\n"
      "  questions: [{id: q, text: \"How?\"}]\n"
      "outputs: {video: false, contact_sheet: false}\n");
  CHECK(s.name == "t");
  CHECK(s.seed == 5);
  CHECK(s.scenario.type == ScenarioKind::corridor);
  CHECK(s.scenario.width_m == 2.5);
  CHECK(s.scenario.depth_m == 8.0);
  CHECK(s.crowd.model == CrowdModel::social);
  CHECK(s.crowd.agent_radius_m == 0.2);
  CHECK(s.crowd.cost_weights.at("goal") == 1.5);
  CHECK(s.crowd.max_neighbors == 10);  // default kept
  REQUIRE(s.factors.size() == 2);
  CHECK(s.factors[0].name == "density");
  CHECK(s.factors[0].levels[1].text == "3.33");
  CHECK(*s.factors[0].levels[1].number == 3.33);
  CHECK_FALSE(s.factors[1].levels[0].number.has_value());
  CHECK(s.duration_s == 12.5);
  CHECK(s.fps == 25.0);
  CHECK(s.render.width == 1280);
  CHECK(s.render.height == 720);
  CHECK(s.render.crf == 23);
  CHECK(s.render.msaa == 4);
  CHECK(s.render.background == "#102030");
  CHECK(s.render.viewpoint_overrides.at(ViewpointId::V3)[6] > 0.0);
  CHECK(s.protocol.type == ProtocolType::rating);
  CHECK(s.protocol.scale_points == 7);
  CHECK(s.protocol.questions.at(0).id == "q");
  CHECK_FALSE(s.outputs.video);
  CHECK_FALSE(s.outputs.contact_sheet);
}

TEST_CASE("the shipped specs load and mirror their papers' designs") {
  const auto dir = test::source_dir() / "experiments";
  const ExperimentSpec st = load_experiment_spec((dir / "gomez2024_stationary.yaml").string());
  CHECK(st.scenario.width_m * st.scenario.depth_m == Approx(9.0));
  CHECK(st.duration_s == 20.0);
  CHECK(st.render.width == 1920);
  CHECK(st.render.height == 1080);
  CHECK(st.protocol.scale_points == 6);
  REQUIRE(st.protocol.questions.size() == 6);
  for (size_t i = 0; i < 6; ++i) CHECK(st.protocol.questions[i].reverse == (i % 2 == 1));  // Q2, Q4, Q6
  REQUIRE(st.protocol.composites.size() == 3);
  // 2.22 .. 6.66 per m^2 on 9 m^2 gives 20 .. 60 characters.
  std::vector<long> counts;
  for (const FactorLevel& l : factor_of(st, "density").levels) counts.push_back(std::lround(*l.number * 9.0));
  CHECK(counts == std::vector<long>{20, 30, 40, 50, 60});
  CHECK(enumerate_conditions(st).size() == 40);

  const ExperimentSpec pairs = load_experiment_spec((dir / "hoyet2016_pairs.yaml").string());
  CHECK(pairs.protocol.type == ProtocolType::two_afc);
  CHECK(pairs.protocol.questions.at(0).kind == "yesno");
  CHECK(pairs.protocol.questions.at(1).kind == "scale");
  CHECK(pairs.protocol.scale_points == 7);
  const Factor* distance = pairs.factor("distance");
  REQUIRE(distance->levels.size() == 11);
  for (size_t i = 0; i < 11; ++i)
    CHECK(*distance->levels[i].number == Approx(0.20 + 0.05 * static_cast<double>(i)));
  CHECK(enumerate_conditions(pairs).size() == 264);
  CHECK(enumerate_practice_conditions(pairs).size() == 6);

  const ExperimentSpec crowds = load_experiment_spec((dir / "hoyet2016_crowds.yaml").string());
  CHECK(enumerate_conditions(crowds).size() == 120);
  CHECK(crowds.protocol.block_by == "scenario");
  // density = 1 / spacing^2 for spacings 0.6 .. 1.4 m, to the paper's one decimal.
  const Factor* density = crowds.factor("density");
  for (size_t i = 0; i < 5; ++i) {
    const double spacing = 0.6 + 0.2 * static_cast<double>(i);
    CHECK(*density->levels[i].number == Approx(1.0 / (spacing * spacing)).margin(0.05));
  }
  CHECK(enumerate_conditions(load_experiment_spec((dir / "gomez2024_nonstationary.yaml").string())).size() ==
        20);
}

TEST_CASE("condition ids follow the factor order and hold a level for every factor") {
  const ExperimentSpec s = load_text(kHeader +
                                     "factors:\n  method: [baseline, ours]\n  distance: [0.2, 0.25]\n"
                                     "repetitions: 3\n");
  const auto conds = enumerate_conditions(s);
  REQUIRE(conds.size() == 12);
  CHECK(conds.front().id == "method-baseline_distance-0.2_rep-1");
  CHECK(conds[1].id == "method-baseline_distance-0.2_rep-2");  // repetition fastest
  CHECK(conds[3].id == "method-baseline_distance-0.25_rep-1");
  CHECK(conds.back().id == "method-ours_distance-0.25_rep-3");
  std::set<std::string> ids;
  std::set<std::uint64_t> seeds;
  for (const Condition& c : conds) {
    ids.insert(c.id);
    seeds.insert(c.seed);
    CHECK(c.levels.size() == 2);
    CHECK(c.seed == derive_seed(5, c.id));
    CHECK_FALSE(c.practice);
    CHECK(c.number("distance", -1.0) > 0.0);
  }
  CHECK(ids.size() == conds.size());
  CHECK(seeds.size() == conds.size());
}

TEST_CASE("adding a level keeps every other condition's id and seed") {
  const std::string before =
      kHeader + "factors:\n  density: [2.22, 4.44]\n  viewpoint: [V1, V4]\nrepetitions: 2\n";
  const std::string after =
      kHeader + "factors:\n  density: [2.22, 3.33, 4.44]\n  viewpoint: [V2, V1, V4]\nrepetitions: 2\n";
  const auto a = enumerate_conditions(load_text(before));
  const auto b = enumerate_conditions(load_text(after));
  CHECK(b.size() == 18);
  std::map<std::string, std::uint64_t> seeds_after;
  for (const Condition& c : b) seeds_after[c.id] = c.seed;
  for (const Condition& c : a) {
    INFO(c.id);
    REQUIRE(seeds_after.count(c.id) == 1);
    CHECK(seeds_after[c.id] == c.seed);
  }
}

TEST_CASE("enumeration is deterministic and follows the spec seed") {
  const std::string text = slurp(test::source_dir() / "experiments" / "hoyet2016_pairs.yaml");
  const auto base = (test::source_dir() / "experiments").string();
  const auto a = enumerate_conditions(load_experiment_spec_text(text, "a", base));
  const auto b = enumerate_conditions(load_experiment_spec_text(text, "b", base));
  REQUIRE(a.size() == b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    CHECK(a[i].id == b[i].id);
    CHECK(a[i].seed == b[i].seed);
  }
  std::string reseeded = text;
  reseeded.replace(reseeded.find("seed: 2016000001"), 16, "seed: 2016000009");
  const auto c = enumerate_conditions(load_experiment_spec_text(reseeded, "c", base));
  size_t same = 0;
  for (size_t i = 0; i < a.size(); ++i) same += a[i].seed == c[i].seed;
  CHECK(same == 0);
}

TEST_CASE("source_hash is the SHA-256 of the YAML text") {
  const std::string text = kHeader + "factors: {method: [ours]}\n";
  CHECK(load_text(text).source_hash == sha256_hex(text));
}

TEST_CASE("factor levels are checked per factor") {
  struct Case {
    std::string factor, levels, message;
  };
  const std::vector<Case> bad = {
      {"density", "[0]", "density level must be in (0, 10]"},
      {"density", "[abc]", "density levels are numbers"},
      {"characters", "[20.5]", "whole numbers"},
      {"characters", "[0]", "must be in [1, 10000]"},
      {"viewpoint", "[V5]", "invalid viewpoint level 'V5'"},
      {"method", "[Ours]", "did you mean 'ours'?"},
      {"shoulder", "[3]", "must be in [0, 2]"},
      {"shoulder", "[0.5]", "whole numbers"},
      {"distance", "[-0.2]", "must be in (0, 10]"},
      {"trigger", "[101]", "must be in [0, 100]"},
      {"trigger", "[33, 33%]", "duplicate level"},
      {"scenario", "[C]", "invalid scenario level 'C'"},
      {"side", "[up]", "invalid side level"},
      {"density", "[]", "at least one level"},
      {"density", "[[1, 2]]", "a level must be a single value"},
      {"density", "{levls: [1]}", "unknown key (did you mean 'levels'?)"},
      {"density", "7", "expected a list of levels"},
      {"density", "[1.50, 1.5]", "duplicate level '1.5' (same as '1.50')"},
      {"densty", "[1]", "unknown key (did you mean 'density'?)"},
  };
  for (const Case& c : bad) {
    const auto errors = errors_of(kHeader + "factors:\n  " + c.factor + ": " + c.levels + "\n");
    INFO(c.factor << ": " << c.levels << "\n" << joined(errors));
    REQUIRE_FALSE(errors.empty());
    for (const std::string& e : errors) CHECK_THAT(e, Catch::StartsWith("t.yaml:5:"));
    CHECK_THAT(joined(errors), Catch::Contains(c.message));
  }
  const auto ok = load_text(kHeader + "factors:\n  trigger: [0, 33%, 100]\n  scenario: [A, B, corridor]\n");
  CHECK(factor_of(ok, "trigger").levels[1].text == "33");
  CHECK(*factor_of(ok, "trigger").levels[1].number == 33.0);
}

TEST_CASE("every section's keys, types and ranges are checked") {
  struct Case {
    std::string yaml, message;
  };
  const std::vector<Case> bad = {
      {"repetitions: 0\n", "repetitions: must be in [1, 1000]"},
      {"duration_s: 0\n", "duration_s: must be in (0, 3600], got 0"},
      {"fps: .inf\n", "fps: must be a finite number"},
      {"resolution: [641, 360]\n", "resolution[0]: width must be even"},
      {"resolution: 640\n", "resolution: expected [width, height]"},
      {"scenario: {type: crowd}\n", "scenario.type: invalid value 'crowd'"},
      {"scenario: {area: {width_m: 0}}\n", "scenario.area.width_m: must be in (0, 1000]"},
      {"scenario: {passing_side: both}\n", "scenario.passing_side: invalid value 'both'"},
      {"scenario: [stationary]\n", "scenario: expected a map of keys, got a list"},
      {"crowd: {agent_radius_m: 1.5}\n", "crowd.agent_radius_m: must be in (0, 1]"},
      {"crowd: {max_neighbours: 3}\n", "did you mean 'max_neighbors'?"},
      {"crowd: {cost_weights: {goal: -1}}\n", "crowd.cost_weights.goal: must be >= 0"},
      // Checked by the spec layer, not minutes into `run` by the cost model (issue 30).
      {"crowd: {cost_weights: {separatoin: 1}}\n",
       "crowd.cost_weights.separatoin: unknown key (did you mean 'separation'?)"},
      {"crowd: {cost_weights: {sigma_m: 0}}\n", "crowd.cost_weights.sigma_m: must be > 0"},
      {"crowd: {cost_weights: {iterations: 500}}\n", "crowd.cost_weights.iterations: must be in [1, 100]"},
      {"crowd: {model: cost}\nscenario: {type: manifold, mesh: floor_wall}\n",
       "crowd.model: a manifold scenario needs 'orca' or 'social', not 'cost'"},
      {"animation: {female_fraction: 1.2}\n", "animation.female_fraction: must be in [0, 1]"},
      {"animation: {motion: clips}\n", "motion: clips needs walk_clips or dance_clips"},
      {"animation: {body_model: smpl}\n", "animation.body_model: invalid value 'smpl'"},
      {"animation: {collision_proxies: fited}\n", "animation.collision_proxies: invalid value 'fited'"},
      {"animation: {walk_clips: [{speed_mps: 1.2}]}\n", "walk_clips[0].file: required key is missing"},
      {"correction: {damping: -0.1}\n", "correction.damping: must be >= 0"},
      {"render: {crf: 60}\n", "render.crf: must be in [0, 51]"},
      {"render: {msaa: 16}\n", "render.msaa: must be in [1, 8]"},
      {"render: {background: red}\n", "render.background: expected a colour '#rrggbb'"},
      {"render: {overlap: 2}\n", "render.overlap: expected true or false"},
      {"render: {viewpoints: {V1: [1, 2, 3]}}\n", "expected 7 numbers"},
      // What `run` refused after `validate` had passed (issue 30): the camera placement's own checks, the
      // needs of a scenario kind named by a `scenario` factor's level, a pair crossing's distance.
      {"render: {viewpoints: {V1: [0, 1, 5, 0, 1, 5, 40]}}\nfactors: {viewpoint: [V1]}\n",
       "render.viewpoints.V1: the camera position equals its target"},
      {"render: {viewpoints: {V1: [0, 1, 5, 0, 1, 0, 0.5]}}\nfactors: {viewpoint: [V1]}\n",
       "render.viewpoints.V1: fov_deg must be in (1, 170)"},
      {"factors: {scenario: [stationary, manifold], density: [1]}\n",
       "scenario.mesh: a manifold scenario needs a mesh"},
      {"crowd: {model: cost}\nfactors: {scenario: [manifold]}\nscenario: {mesh: floor_wall}\n",
       "crowd.model: a manifold scenario needs 'orca' or 'social', not 'cost'"},
      {"scenario: {type: pair_crossing}\n", "a pair_crossing scenario needs a `distance` factor"},
      {"outputs: {videos: true}\n", "outputs.videos: unknown key (did you mean 'video'?)"},
      {"protocol: {type: likert}\n", "protocol.questions: required key is missing"},
      {"protocol: {type: lickert, questions: [{id: a, text: b}]}\n", "did you mean 'likert'?"},
      {"protocol: {scale: {points: 1}, questions: [{id: a, text: b}]}\n",
       "protocol.scale.points: must be in [2, 11]"},
      {"protocol: {scale: {points: 5, labels: [a, b, c]}, questions: [{id: a, text: b}]}\n",
       "give 2 anchor labels (lowest, highest) or one per point (5), got 3"},
      {"protocol: {questions: [{id: a, text: b}, {id: a, text: c}]}\n", "duplicate question id 'a'"},
      {"protocol: {questions: [{id: a}]}\n", "protocol.questions[0].text: required key is missing"},
      {"protocol: {questions: [{id: 'a b', text: c}]}\n", "question ids may only contain"},
      {"protocol: {type: 2afc, questions: [{id: a, text: b}]}\n", "needs a question of kind: yesno"},
      {"protocol: {questions: [{id: a, text: b, kind: yesno, reverse: true}]}\n", "cannot be reverse-keyed"},
      {"protocol: {questions: [{id: a, text: b}], composites: [{id: c, items: [z]}]}\n",
       "'z' is not a scale question"},
      {"protocol: {questions: [{id: a, text: b}], block_by: density}\n",
       "'density' is not a factor of this spec"},
      {"protocol: {questions: [{id: a, text: b}], practice: {viewpoint: [V1]}}\n",
       "practice names a factor the spec does not declare"},
      {"protocol: {questions: [{id: a, text: b}], block_order: sorted}\n",
       "protocol.block_order: invalid value"},
  };
  for (const Case& c : bad) {
    const auto errors = errors_of(kHeader + c.yaml);
    INFO(c.yaml << joined(errors));
    REQUIRE(errors.size() == 1);
    CHECK_THAT(errors[0], Catch::StartsWith("t.yaml:4:") || Catch::StartsWith("t.yaml:1:") ||
                              Catch::StartsWith("t.yaml:2:") || Catch::StartsWith("t.yaml:3:"));
    CHECK_THAT(errors[0], Catch::Contains(c.message));
  }
}

TEST_CASE("duplicate keys, a missing name and a non-map document are errors") {
  CHECK_THAT(joined(errors_of("name: t\ncrowdlab: 2\n")),
             Catch::Contains("t.yaml:2:11: crowdlab: must be in [1, 1]"));
  CHECK_THAT(joined(errors_of("name: t\nseed: -4\n")),
             Catch::Contains("t.yaml:2:7: seed: expected a whole number in [0, 2^64)"));
  CHECK_THAT(joined(errors_of(kHeader + "fps: 30\nfps: 25\n")),
             Catch::Contains("t.yaml:5:1: fps: duplicate key"));
  CHECK_THAT(joined(errors_of("crowdlab: 1\n")), Catch::Contains("name: required key is missing"));
  CHECK_THAT(joined(errors_of("name: [a]\n")),
             Catch::Contains("t.yaml:1:7: name: expected text, got a list"));
  CHECK_THAT(joined(errors_of("- a\n- b\n")), Catch::Contains("a spec is a map of keys"));
  CHECK_THAT(joined(errors_of("name: a\nfactors: {density: [1, 2\n")), Catch::Contains("YAML syntax error"));
}

TEST_CASE("referenced files resolve against the spec folder and must exist") {
  const auto dir = test::scratch_dir("spec-files");
  std::filesystem::create_directories(dir / "clips" / "body");
  std::ofstream(dir / "clips" / "walk.bvh") << "HIERARCHY\n";
  std::ofstream(dir / "clips" / "dance.bvh") << "HIERARCHY\n";
  const std::string anim =
      "animation:\n  motion: clips\n  walk_clips: [{file: clips/walk.bvh, speed_mps: 1.2}]\n"
      "  dance_clips: [clips/dance.bvh]\n  body_model: {type: mpfb2, path: clips/body}\n";
  const ExperimentSpec s = load_text(kHeader + anim, dir.string());
  REQUIRE(s.animation.walk_clips.size() == 1);
  CHECK(std::filesystem::equivalent(s.animation.walk_clips[0], dir / "clips" / "walk.bvh"));
  CHECK(s.animation.walk_clip_speeds_mps[0] == 1.2);
  CHECK(std::filesystem::equivalent(s.animation.dance_clips.at(0), dir / "clips" / "dance.bvh"));
  CHECK(std::filesystem::equivalent(s.animation.body_model_path, dir / "clips" / "body"));
  CHECK(s.animation.body_model == BodyModel::mpfb2);
  // From another folder the same relative paths are missing: three errors, each with its line.
  const auto errors = errors_of(kHeader + anim, (dir / "elsewhere").string());
  REQUIRE(errors.size() == 3);
  CHECK_THAT(errors[0],
             Catch::StartsWith("t.yaml:6:") && Catch::Contains("walk_clips[0].file: file not found"));
  CHECK_THAT(errors[1], Catch::StartsWith("t.yaml:7:") && Catch::Contains("dance_clips[0]: file not found"));
  CHECK_THAT(errors[2],
             Catch::StartsWith("t.yaml:8:") && Catch::Contains("body_model.path: folder not found"));
  // A file where a folder is expected is an error too.
  CHECK_THAT(joined(errors_of(kHeader + "animation: {body_model: {type: mpfb2, path: clips/walk.bvh}}\n",
                              dir.string())),
             Catch::Contains("folder not found"));
  CHECK_THAT(joined(errors_of(kHeader + "scenario: {type: manifold, mesh: hills.obj}\n", dir.string())),
             Catch::Contains("scenario.mesh: file not found: 'hills.obj'"));
}

TEST_CASE("practice trials: crossing of the practice levels, one set per block") {
  const auto dir = test::source_dir() / "experiments";
  const ExperimentSpec pairs = load_experiment_spec((dir / "hoyet2016_pairs.yaml").string());
  const auto practice = enumerate_practice_conditions(pairs);
  REQUIRE(practice.size() == 6);
  std::set<std::string> main_ids;
  for (const Condition& c : enumerate_conditions(pairs)) main_ids.insert(c.id);
  for (const Condition& c : practice) {
    CHECK(c.practice);
    CHECK_THAT(c.id, Catch::StartsWith("practice_shoulder-"));
    CHECK(main_ids.count(c.id) == 0);
    CHECK(c.seed == derive_seed(pairs.seed, c.id));
    CHECK(c.text("viewpoint", "") == "pair");  // factors not named in practice take their first level
    const double d = c.number("distance", 0.0);
    CHECK((d == 0.2 || d == 0.7));
  }
  const ExperimentSpec crowds = load_experiment_spec((dir / "hoyet2016_crowds.yaml").string());
  const auto per_block = enumerate_practice_conditions(crowds);
  REQUIRE(per_block.size() == 12);
  int in_a = 0;
  for (const Condition& c : per_block) in_a += c.text("scenario", "") == "A";
  CHECK(in_a == 6);
  CHECK(enumerate_practice_conditions(load_text(kHeader + "factors: {method: [ours]}\n")).empty());
}

TEST_CASE("a spec without factors has one condition per repetition") {
  const auto conds = enumerate_conditions(load_text(kHeader + "repetitions: 3\n"));
  REQUIRE(conds.size() == 3);
  CHECK(conds[0].id == "rep-1");
  CHECK(conds[2].id == "rep-3");
}

TEST_CASE("truncated and mangled specs give SpecError, never a crash") {
  const std::string text = slurp(test::source_dir() / "experiments" / "hoyet2016_crowds.yaml");
  const size_t step = test::kSanitized ? 37 : 7;
  int failures = 0;
  for (size_t n = 0; n < text.size(); n += step) {
    for (const std::string& variant :
         {text.substr(0, n), text.substr(0, n) + "\x01\t: [{\n" + text.substr(n)}) {
      try {
        load_experiment_spec_text(variant, "cut.yaml", ".");
      } catch (const SpecError& e) {
        ++failures;
        for (const std::string& m : e.messages()) CHECK_THAT(m, Catch::StartsWith("cut.yaml"));
      }
    }
  }
  CHECK(failures > 0);
}

TEST_CASE("edit distance and suggestions") {
  CHECK(edit_distance("kitten", "sitting") == 3);
  CHECK(edit_distance("", "abc") == 3);
  CHECK(edit_distance("Density", "density") == 0);
  CHECK(closest_match("viewpont", {"viewpoint", "method"}) == "viewpoint");
  CHECK(closest_match("zzzzzz", {"viewpoint", "method"}).empty());
  CHECK(suggestion_suffix("zzz", {"a", "b"}) == " (expected one of: a, b)");
}

TEST_CASE("typed conditions: the scenario follows the scenario factor, with A/B as flows") {
  const ExperimentSpec s =
      load_text(kHeader + "scenario: {type: corridor}\nfactors: {scenario: [A, B, stationary]}\n");
  const auto conds = enumerate_conditions(s);
  REQUIRE(conds.size() == 3);
  CHECK(conds[0].params.scenario == ScenarioKind::flow_a);
  CHECK(conds[1].params.scenario == ScenarioKind::flow_b);
  CHECK(conds[2].params.scenario == ScenarioKind::stationary);
  const ExperimentSpec plain = load_text(kHeader + "scenario: {type: corridor}\n");
  CHECK(enumerate_conditions(plain).at(0).params.scenario == ScenarioKind::corridor);
}

}  // namespace test_spec_loader
