// The stage recipes (framework/pipeline/crowd_recipes.hpp, stimuli/presentation_recipes.hpp) hold
// exactly what each stage reads (issue 30): every spec value is edited in turn and the recipes whose
// canonical bytes change, i.e. the stages whose input hash changes, must be exactly the stages that
// read it. Values no stage reads (the protocol but for loop_video, the outputs' switches, the name) change
// no recipe.
#include <catch2/catch.hpp>
#include <functional>
#include <map>
#include <set>

#include "framework/core/canonical_bytes.hpp"
#include "framework/crowd/generate_scenario.hpp"
#include "framework/pipeline/crowd_key.hpp"
#include "framework/pipeline/crowd_recipes.hpp"
#include "framework/spec/load_experiment_spec.hpp"
#include "stimuli/presentation_recipes.hpp"
#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_stage_recipes {

using namespace crowdlab;
using namespace crowdlab::test;

namespace {

/// The paths of a stage's input files as text (they are hashed by content when the stage runs; here,
/// which files a stage reads is what counts).
std::string files(const std::vector<std::filesystem::path>& paths) {
  std::vector<std::string> text;
  for (const auto& p : paths) text.push_back(p.string());
  return canonical_bytes(text);
}

/// Each stage's recipe bytes for the spec's first condition.
std::map<std::string, std::string> recipe_bytes(const ExperimentSpec& spec) {
  const CrowdGroupRecipes r = crowd_group_recipes(spec, enumerate_conditions(spec).front());
  return {
      {"crowd", canonical_bytes(r.crowd) + files(r.crowd_files)},
      {"animation", canonical_bytes(r.animation) + files(r.animation_files)},
      {"correction", canonical_bytes(r.correction)},
      {"metrics", canonical_bytes(metrics_recipe(r, CrowdMethod::corrected))},
      {"render", canonical_bytes(stimuli::render_recipe(spec, ViewpointId::V4))},
      {"contact_sheet", canonical_bytes(stimuli::ContactSheetRecipe{stimuli::stimulus_look(spec.render)})},
      {"stimulus_check", canonical_bytes(stimuli::stimulus_check_recipe(spec, ViewpointId::V4))}};
}

struct Edit {
  const char* what;
  std::function<void(ExperimentSpec&)> apply;
  std::set<std::string> stages;  ///< whose recipes must change
};

}  // namespace

TEST_CASE("stage recipes: every spec value changes exactly the recipes of the stages that read it") {
  const ExperimentSpec base = load_experiment_spec(tiny_spec());
  const std::set<std::string> none, crowd{"crowd"}, animation{"animation"},
      look{"render", "contact_sheet", "stimulus_check"};
  const std::vector<Edit> edits{
      {"scenario.width_m", [](ExperimentSpec& s) { s.scenario.width_m += 1; }, crowd},
      {"scenario.depth_m", [](ExperimentSpec& s) { s.scenario.depth_m += 1; }, crowd},
      {"scenario.stage_direction_deg", [](ExperimentSpec& s) { s.scenario.stage_direction_deg = 90; }, crowd},
      // tiny.yaml is a stationary crowd sized by density: it reads neither the walking nor the navigation
      // model's values (the other kinds: the test below).
      {"scenario.walk_speed_mps", [](ExperimentSpec& s) { s.scenario.walk_speed_mps = 1.1; }, none},
      {"scenario.initial_spacing_m", [](ExperimentSpec& s) { s.scenario.initial_spacing_m = 0.8; }, none},
      {"scenario.passing_side", [](ExperimentSpec& s) { s.scenario.passing_side = PassingSide::right; },
       none},
      {"scenario.agents", [](ExperimentSpec& s) { s.scenario.agents = 12; }, none},
      {"scenario.mesh", [](ExperimentSpec& s) { s.scenario.mesh = "stairs"; }, none},
      {"crowd.model", [](ExperimentSpec& s) { s.crowd.model = CrowdModel::social; }, none},
      {"crowd.agent_radius_m", [](ExperimentSpec& s) { s.crowd.agent_radius_m = 0.2; }, crowd},
      {"crowd.personal_space_m", [](ExperimentSpec& s) { s.crowd.personal_space_m = 0.5; }, crowd},
      {"crowd.neighbor_distance_m", [](ExperimentSpec& s) { s.crowd.neighbor_distance_m = 3; }, none},
      {"crowd.max_neighbors", [](ExperimentSpec& s) { s.crowd.max_neighbors = 5; }, none},
      {"crowd.time_horizon_s", [](ExperimentSpec& s) { s.crowd.time_horizon_s = 3; }, none},
      {"crowd.obstacle_time_horizon_s", [](ExperimentSpec& s) { s.crowd.obstacle_time_horizon_s = 3; }, none},
      {"crowd.max_speed_mps", [](ExperimentSpec& s) { s.crowd.max_speed_mps = 2; }, none},
      {"crowd.dt_s", [](ExperimentSpec& s) { s.crowd.dt_s = 0.05; }, none},
      {"crowd.overlap_free", [](ExperimentSpec& s) { s.crowd.overlap_free = true; }, none},
      {"crowd.cost_weights", [](ExperimentSpec& s) { s.crowd.cost_weights["goal"] = 2; }, none},
      {"duration_s", [](ExperimentSpec& s) { s.duration_s = 1.5; }, crowd},
      // A looping clip of 2 s or more gets the loop pre-roll (kLoopPrerollMinClipS): the correction reads it.
      {"duration_s", [](ExperimentSpec& s) { s.duration_s = 2; }, {"correction", "crowd"}},
      {"fps", [](ExperimentSpec& s) { s.fps = 30; }, crowd},
      {"seed", [](ExperimentSpec& s) { s.seed = 8; }, {"crowd", "animation"}},
      {"animation.body_model", [](ExperimentSpec& s) { s.animation.body_model = BodyModel::mpfb2; },
       animation},
      {"animation.female_fraction", [](ExperimentSpec& s) { s.animation.female_fraction = 0.3; }, animation},
      {"animation.ttca_threshold_s", [](ExperimentSpec& s) { s.animation.ttca_threshold_s = 1; }, animation},
      {"animation.dtca_threshold_m", [](ExperimentSpec& s) { s.animation.dtca_threshold_m = 1; }, animation},
      {"animation.motion", [](ExperimentSpec& s) { s.animation.motion = MotionSource::clips; }, animation},
      {"animation.dance_clips", [](ExperimentSpec& s) { s.animation.dance_clips = {"d.bvh"}; }, animation},
      {"animation.walk_clips", [](ExperimentSpec& s) { s.animation.walk_clips = {"w.bvh"}; }, animation},
      {"animation.walk_clip_speeds_mps", [](ExperimentSpec& s) { s.animation.walk_clip_speeds_mps = {1}; },
       animation},
      // tiny.yaml's procedural bodies resolve `auto` to `volume`: asking for fitted capsules changes them.
      {"animation.collision_proxies",
       [](ExperimentSpec& s) { s.animation.collision_proxies = CollisionProxies::fitted; }, animation},
      {"animation.collision_proxies: volume, what auto resolves to here",
       [](ExperimentSpec& s) { s.animation.collision_proxies = CollisionProxies::volume; }, none},
      {"correction.stiffness", [](ExperimentSpec& s) { s.correction.stiffness = 10; }, {"correction"}},
      {"correction.damping", [](ExperimentSpec& s) { s.correction.damping = 0.01; }, {"correction"}},
      {"correction.collision_stiffness",
       [](ExperimentSpec& s) { s.correction.collision_stiffness = 5; },
       {"correction"}},
      {"render.width", [](ExperimentSpec& s) { s.render.width = 320; }, look},
      {"render.height", [](ExperimentSpec& s) { s.render.height = 192; }, look},
      {"render.msaa", [](ExperimentSpec& s) { s.render.msaa = 4; }, look},
      {"render.overlap", [](ExperimentSpec& s) { s.render.overlap = true; }, look},
      {"render.background", [](ExperimentSpec& s) { s.render.background = "#000000"; }, look},
      {"render.fog", [](ExperimentSpec& s) { s.render.fog = true; }, look},
      {"render.viewpoints",
       [](ExperimentSpec& s) { s.render.viewpoint_overrides[ViewpointId::V4] = {0, 9, 1, 0, 0, 0, 40}; },
       look},
      {"render.characters", [](ExperimentSpec& s) { s.render.characters = {"c.glb"}; }, look},
      {"render.crf", [](ExperimentSpec& s) { s.render.crf = 23; }, {"render"}},
      {"render.frames_png", [](ExperimentSpec& s) { s.render.frames_png = true; }, {"render"}},
      {"render.check.overlap_every_frames",
       [](ExperimentSpec& s) { s.render.check.overlap_every_frames = 5; },
       {"render", "stimulus_check"}},
      {"render.check's thresholds", [](ExperimentSpec& s) { s.render.check.character_height_px_min = 1; },
       none},
      {"protocol.instructions", [](ExperimentSpec& s) { s.protocol.instructions = "Watch."; }, none},
      {"protocol.questions", [](ExperimentSpec& s) { s.protocol.questions.at(0).text = "Other"; }, none},
      {"protocol.type", [](ExperimentSpec& s) { s.protocol.type = ProtocolType::rating; }, none},
      {"protocol.break_every", [](ExperimentSpec& s) { s.protocol.break_every = 3; }, none},
      // Looping clips: the free-limb window wraps around the loop (tiny.yaml's 1 s clips get no loop
      // pre-roll, so the correction does not change).
      {"protocol.loop_video", [](ExperimentSpec& s) { s.protocol.loop_video = false; }, {"metrics"}},
      {"outputs.contact_sheet", [](ExperimentSpec& s) { s.outputs.contact_sheet = true; }, none},
      {"outputs.metrics", [](ExperimentSpec& s) { s.outputs.metrics = false; }, none},
      {"name", [](ExperimentSpec& s) { s.name = "other"; }, none},
      {"description", [](ExperimentSpec& s) { s.description = "other"; }, none},
      {"the YAML text", [](ExperimentSpec& s) { s.source_hash = "0000"; }, none},
  };
  const auto before = recipe_bytes(base);
  for (const Edit& e : edits) {
    INFO(e.what);
    ExperimentSpec spec = base;
    e.apply(spec);
    std::set<std::string> changed;
    for (const auto& [stage, bytes] : recipe_bytes(spec))
      if (bytes != before.at(stage)) changed.insert(stage);
    CHECK(changed == e.stages);
  }
}

TEST_CASE("stage recipes: leaving the mesh-level measures out changes the metrics recipe") {
  // RunOptions::mesh_measures (`reproduce gomez2024 --quick`, issue 31) is read by the metrics stage
  // only: a metrics.json with the measures and one without must not pass for each other.
  const ExperimentSpec spec = load_experiment_spec(tiny_spec());
  CrowdGroupRecipes with = crowd_group_recipes(spec, enumerate_conditions(spec).front());
  with.mesh_measures = true;
  CrowdGroupRecipes without = with;
  without.mesh_measures = false;
  for (const CrowdMethod m : {CrowdMethod::baseline, CrowdMethod::corrected})
    CHECK(canonical_bytes(metrics_recipe(without, m)) != canonical_bytes(metrics_recipe(with, m)));
}

TEST_CASE("stage recipes: the MPFB2 folder is part of the animation recipe only with MPFB2 bodies") {
  ExperimentSpec spec = load_experiment_spec(tiny_spec());
  const Condition first = enumerate_conditions(spec).front();
  const std::string procedural = canonical_bytes(crowd_group_recipes(spec, first).animation);
  spec.animation.body_model_path = "/elsewhere";
  CHECK(canonical_bytes(crowd_group_recipes(spec, first).animation) == procedural);
  spec.animation.body_model = BodyModel::mpfb2;
  const std::string mpfb2 = canonical_bytes(crowd_group_recipes(spec, first).animation);
  spec.animation.body_model_path = "/other";
  CHECK(canonical_bytes(crowd_group_recipes(spec, first).animation) != mpfb2);
}

TEST_CASE("stage recipes: every viewpoint and method of a crowd group share its crowd recipes") {
  const ExperimentSpec spec = load_experiment_spec(tiny_spec());
  std::map<std::string, std::set<std::string>> by_key;  // crowd key -> crowd + animation recipe bytes
  for (const Condition& c : enumerate_conditions(spec)) {
    const CrowdGroupRecipes r = crowd_group_recipes(spec, c);
    by_key[r.animation.key].insert(canonical_bytes(r.crowd) + canonical_bytes(r.animation));
  }
  CHECK(by_key.size() == 3);
  for (const auto& [key, recipes] : by_key) {
    INFO(key);
    CHECK(recipes.size() == 1);
  }
}

namespace {

/// The generator's output as text: every agent's radius, group and positions and headings per frame.
std::string trajectories_text(const ScenarioResult& r) {
  std::string out;
  for (const AgentTrajectory& a : r.trajectories.agents) {
    out += std::to_string(a.radius_m) + "/" + std::to_string(a.group) + ":";
    for (size_t f = 0; f < a.position_m.size(); ++f)
      out += std::to_string(a.position_m[f].x()) + "," + std::to_string(a.position_m[f].y()) + "," +
             std::to_string(a.heading_rad[f]) + ";";
  }
  return out;
}

/// tiny.yaml with its scenario section, factors (besides viewpoint and method) and crowd section replaced.
ExperimentSpec kind_spec(const std::string& scenario, const std::string& factors, const std::string& crowd) {
  std::string yaml = slurp(tiny_spec());
  const auto replace_block = [&](const std::string& from, const std::string& to, const std::string& with) {
    const size_t a = yaml.find(from), b = yaml.find(to, a);
    REQUIRE(a != std::string::npos);
    REQUIRE(b != std::string::npos);
    yaml.replace(a, b - a, with);
  };
  replace_block("scenario:\n", "factors:\n", "scenario: " + scenario + "\ncrowd: " + crowd + "\n");
  replace_block("  density:", "  viewpoint:", factors);
  return load_experiment_spec_text(yaml, "kind.yaml",
                                   std::filesystem::path(tiny_spec()).parent_path().string());
}

}  // namespace

TEST_CASE("stage recipes: a crowd recipe holds only the values its scenario kind reads") {
  // Each kind's crowd recipe ignores some spec values (they do not redo its crowd), and for every value it
  // ignores the generator's trajectories are unchanged: the recipe covers everything the generator reads.
  struct Kind {
    const char* name;
    ExperimentSpec spec;
    std::set<std::string> ignored;  ///< edits that must not change the crowd recipe
  };
  const std::vector<Kind> kinds{
      {"stationary",
       kind_spec("{type: stationary, area: {width_m: 1.5, depth_m: 1.5}}", "  density: [2.5]\n",
                 "{agent_radius_m: 0.18}"),
       {"walk_speed", "spacing", "side", "agents", "model", "neighbours", "horizon", "speed", "dt", "cost"}},
      {"corridor",
       kind_spec("{type: corridor, area: {width_m: 2, depth_m: 6}}", "  density: [0.8]\n",
                 "{agent_radius_m: 0.2}"),
       {"direction", "spacing", "side", "agents", "cost"}},
      {"pair_crossing",
       kind_spec("{type: pair_crossing, area: {width_m: 4, depth_m: 4}}", "  distance: [0.5]\n",
                 "{agent_radius_m: 0.2}"),
       {"direction", "spacing", "agents", "model", "neighbours", "horizon", "speed", "dt", "cost",
        "personal"}},
      {"flow_b",
       kind_spec("{type: flow_b, area: {width_m: 3, depth_m: 4}, initial_spacing_m: 1.0}",
                 "  characters: [6]\n", "{agent_radius_m: 0.2, model: social}"),
       {"direction", "side", "neighbours", "horizon", "cost", "personal"}},
  };
  const std::vector<std::pair<std::string, std::function<void(ExperimentSpec&)>>> edits{
      {"width", [](ExperimentSpec& s) { s.scenario.width_m += 0.5; }},
      {"direction", [](ExperimentSpec& s) { s.scenario.stage_direction_deg = 90; }},
      {"walk_speed", [](ExperimentSpec& s) { s.scenario.walk_speed_mps = 1.0; }},
      {"spacing", [](ExperimentSpec& s) { s.scenario.initial_spacing_m = 0.8; }},
      {"side", [](ExperimentSpec& s) { s.scenario.passing_side = PassingSide::right; }},
      {"agents", [](ExperimentSpec& s) { s.scenario.agents = 4; }},
      {"model", [](ExperimentSpec& s) { s.crowd.model = CrowdModel::none; }},
      {"neighbours", [](ExperimentSpec& s) { s.crowd.max_neighbors = 1; }},
      {"horizon", [](ExperimentSpec& s) { s.crowd.time_horizon_s = 0.2; }},
      {"speed", [](ExperimentSpec& s) { s.crowd.max_speed_mps = 0.5; }},
      {"dt", [](ExperimentSpec& s) { s.crowd.dt_s = 0.05; }},
      {"cost", [](ExperimentSpec& s) { s.crowd.cost_weights["goal"] = 2; }},
      {"personal", [](ExperimentSpec& s) { s.crowd.personal_space_m = 0.6; }},
      {"radius", [](ExperimentSpec& s) { s.crowd.agent_radius_m = 0.15; }},
  };
  for (const Kind& k : kinds) {
    const Condition first = enumerate_conditions(k.spec).front();
    const std::string recipe = canonical_bytes(crowd_group_recipes(k.spec, first).crowd);
    const std::string trajectories =
        trajectories_text(generate_scenario(k.spec, crowd_condition(k.spec, first)));
    for (const auto& [what, apply] : edits) {
      INFO(k.name << ": " << what);
      ExperimentSpec edited = k.spec;
      apply(edited);
      const Condition edited_first = enumerate_conditions(edited).front();
      const bool same_recipe = canonical_bytes(crowd_group_recipes(edited, edited_first).crowd) == recipe;
      CHECK(same_recipe == (k.ignored.count(what) == 1));
      if (same_recipe)
        CHECK(trajectories_text(generate_scenario(edited, crowd_condition(edited, edited_first))) ==
              trajectories);
    }
  }
}

TEST_CASE(
    "stage recipes: crowds that walk on the flat ground follow their corrected roots and keep their "
    "feet on the input's ground, others do not",
    "[pipeline]") {
  // Session 27 (follow_root_offsets.hpp, walking_correction): the correction of a walking crowd runs twice,
  // the second time toward its input moved onto the first run's roots, with planted feet on the input's
  // ground. Standing crowds and crowds on surfaces run once, as before.
  auto walking = [](const ExperimentSpec& spec) {
    return crowd_group_recipes(spec, enumerate_conditions(spec).front()).correction.walking;
  };
  CHECK(walking(kind_spec("{type: corridor, area: {width_m: 2, depth_m: 6}}", "  density: [0.8]\n",
                          "{agent_radius_m: 0.2}")));
  CHECK(walking(kind_spec("{type: flow_b, area: {width_m: 3, depth_m: 4}, initial_spacing_m: 1.0}",
                          "  characters: [6]\n", "{agent_radius_m: 0.2, model: social}")));
  CHECK_FALSE(walking(kind_spec("{type: stationary, area: {width_m: 1.5, depth_m: 1.5}}",
                                "  density: [2.5]\n", "{agent_radius_m: 0.18}")));
  CHECK_FALSE(walking(load_experiment_spec((source_dir() / "experiments/manifold_demo.yaml").string())));
  CHECK(walking(load_experiment_spec((source_dir() / "experiments/gomez2024_nonstationary.yaml").string())));
  CHECK_FALSE(
      walking(load_experiment_spec((source_dir() / "experiments/gomez2024_stationary.yaml").string())));
  // What a walking crowd's correction is given; the corrector's own defaults are a standing crowd's.
  CorrectorParams params;
  CHECK(params.follow_root_smoothing_s == 0.0);
  CHECK_FALSE(params.held_feet_at_input_height);
  CHECK_FALSE(params.feet_above_input_ground);
  walking_correction(params);
  CHECK(params.follow_root_smoothing_s == kWalkingFollowRootS);
  CHECK(params.held_feet_at_input_height);
  CHECK(params.feet_above_input_ground);
}

TEST_CASE(
    "stage recipes: a looping clip of at least 2 s gets the loop pre-roll, over half the clip up to 2 s",
    "[pipeline][loop]") {
  ExperimentSpec spec = load_experiment_spec((source_dir() / "tests/data/pipeline/loop_seam.yaml").string());
  REQUIRE(spec.protocol.loop_video);
  auto preroll = [&] {
    return crowd_group_recipes(spec, enumerate_conditions(spec).front()).correction.loop_preroll_s;
  };
  spec.duration_s = 20.0;
  CHECK(preroll() == kLoopPrerollS);
  spec.duration_s = 2.0 * kLoopPrerollS;
  CHECK(preroll() == kLoopPrerollS);
  // The demo's 2 s clips close over their last second.
  spec.duration_s = kLoopPrerollMinClipS;
  CHECK(preroll() == Approx(0.5 * kLoopPrerollMinClipS));
  spec.duration_s = 3.0;
  CHECK(preroll() == Approx(1.5));
  // A shorter clip stays open: the closing blend would span most of it and edit limbs that touch nobody.
  spec.duration_s = 1.0;
  CHECK(preroll() == 0.0);
  spec.duration_s = kLoopPrerollMinClipS;
  spec.protocol.loop_video = false;
  CHECK(preroll() == 0.0);
}

}  // namespace test_stage_recipes
