// `crowdlab validate SPEC.yaml`: checks a spec and prints its design (summary + condition table).
// Invalid specs print every problem as "file:line:column: key.path: message" and exit with code 2.
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "experiments/cli/command_table.hpp"
#include "framework/animation/import_motion_clip.hpp"
#include "framework/crowd/check_crowd_size_known.hpp"
#include "framework/pipeline/body_model.hpp"
#include "framework/spec/load_experiment_spec.hpp"
#include "framework/spec/locate_spec_key.hpp"
#include "framework/surface/spec_surface.hpp"
#include "stimuli/gltf_character.hpp"

namespace crowdlab::cli::cmd_validate {
namespace {

struct ValidateOptions {
  std::string spec_path;
  bool no_table = false;
};

std::string levels_text(const Factor& f) {
  std::string s;
  for (const FactorLevel& l : f.levels) s += (s.empty() ? "" : ", ") + l.text;
  return s;
}

void print_summary(const ExperimentSpec& spec) {
  std::printf("spec:        %s\n", spec.source_path.c_str());
  std::printf("name:        %s\n", spec.name.c_str());
  if (!spec.description.empty()) std::printf("description: %s\n", spec.description.c_str());
  std::printf("sha256:      %s\n", spec.source_hash.c_str());
  std::printf("seed:        %llu\n", static_cast<unsigned long long>(spec.seed));
  const std::string scenario(kind_name(spec.scenario.type));
  if (spec.scenario.type == ScenarioKind::pair_crossing || spec.scenario.type == ScenarioKind::manifold)
    std::printf("scenario:    %s\n", scenario.c_str());
  else
    std::printf("scenario:    %s (%.6g m x %.6g m)\n", scenario.c_str(), spec.scenario.width_m,
                spec.scenario.depth_m);
  std::printf("crowd model: %s, agent radius %.6g m\n", std::string(kind_name(spec.crowd.model)).c_str(),
              spec.crowd.agent_radius_m);
  std::printf("clips:       %.6g s at %.6g fps, %dx%d\n", spec.duration_s, spec.fps, spec.render.width,
              spec.render.height);
  std::printf("factors:\n");
  for (const Factor& f : spec.factors)
    std::printf("  %-11s %zu level%s: %s\n", f.name.c_str(), f.levels.size(), f.levels.size() == 1 ? "" : "s",
                levels_text(f).c_str());
  std::printf("repetitions: %d\n", spec.repetitions);
  const ProtocolSpec& p = spec.protocol;
  std::printf("protocol:    %s, %zu question(s), %d-point scale", std::string(kind_name(p.type)).c_str(),
              p.questions.size(), p.scale_points);
  if (!p.block_by.empty())
    std::printf(", blocks by %s (%s order)", p.block_by.c_str(),
                std::string(kind_name(p.block_order)).c_str());
  std::printf("\n");
  int w = 0;
  for (const QuestionSpec& q : p.questions) w = std::max(w, static_cast<int>(q.id.size()));
  for (const CompositeSpec& c : p.composites) w = std::max(w, static_cast<int>(c.id.size()));
  for (const QuestionSpec& q : p.questions)
    std::printf("  %-*s %s%s%s\n", w, q.id.c_str(), q.kind == "yesno" ? "[yes/no] " : "", q.text.c_str(),
                q.reverse ? "  (reverse-keyed)" : "");
  for (const CompositeSpec& c : p.composites) {
    std::string items;
    for (const std::string& i : c.items) items += (items.empty() ? "" : " + ") + i;
    std::printf("  %-*s = mean(%s)\n", w, c.id.c_str(), items.c_str());
  }
}

void print_table(const ExperimentSpec& spec, const std::vector<Condition>& conditions) {
  size_t id_width = 2;
  for (const Condition& c : conditions) id_width = std::max(id_width, c.id.size());
  std::vector<size_t> widths;
  for (const Factor& f : spec.factors) {
    size_t w = f.name.size();
    for (const FactorLevel& l : f.levels) w = std::max(w, l.text.size());
    widths.push_back(w);
  }
  std::printf("%-*s", static_cast<int>(id_width), "id");
  for (size_t i = 0; i < spec.factors.size(); ++i)
    std::printf("  %-*s", static_cast<int>(widths[i]), spec.factors[i].name.c_str());
  std::printf("  %3s  %20s\n", "rep", "seed");
  for (const Condition& c : conditions) {
    std::printf("%-*s", static_cast<int>(id_width), c.id.c_str());
    for (size_t i = 0; i < spec.factors.size(); ++i)
      std::printf("  %-*s", static_cast<int>(widths[i]), c.text(spec.factors[i].name, "-").c_str());
    std::printf("  %3d  %20llu\n", c.repetition, static_cast<unsigned long long>(c.seed));
  }
}

// Reads a file the spec names as `run` would; its problems are prefixed with the spec key's place.
template <class Read>
void read_referenced(const ExperimentSpec& spec, const std::string& key, Read&& read) {
  try {
    read();
  } catch (const InputError& e) {
    throw InputError(locate_spec_key(spec.source_path, key), e.what());
  }
}

// The files `run` parses beyond the spec (issue 33 item 2: a clip or character that was not a clip or a
// character passed validate, and `run` refused it later without the spec's line): the motion clips of
// the scenario kinds the conditions use (dance clips for stationary crowds, walk clips otherwise), and
// the MPFB2 asset folder of animation.body_model and the glTF characters of render.characters.
void read_referenced_files(const ExperimentSpec& spec, const std::vector<Condition>& conditions) {
  const AnimationSpec& a = spec.animation;
  if (a.motion == MotionSource::clips) {
    bool stationary = false, walking = false;
    for (const Condition& c : conditions) {
      stationary = stationary || c.params.scenario == ScenarioKind::stationary;
      walking = walking || c.params.scenario != ScenarioKind::stationary;
    }
    for (size_t i = 0; stationary && i < a.dance_clips.size(); ++i)
      read_referenced(spec, "animation.dance_clips[" + std::to_string(i) + "]",
                      [&] { import_motion_clip(a.dance_clips[i]); });
    for (size_t i = 0; walking && i < a.walk_clips.size(); ++i)
      read_referenced(spec, "animation.walk_clips[" + std::to_string(i) + "].file",
                      [&] { import_motion_clip(a.walk_clips[i]); });
  }
  if (a.body_model == BodyModel::mpfb2)
    read_referenced(spec, "animation.body_model", [&] { load_body_model_assets(a); });
  for (size_t i = 0; i < spec.render.characters.size(); ++i)
    read_referenced(spec, "render.characters[" + std::to_string(i) + "]",
                    [&] { stimuli::load_gltf_character(spec.render.characters[i]); });
}

void run_validate(const ValidateOptions& opt) {
  ExperimentSpec spec;
  try {
    spec = load_experiment_spec(opt.spec_path);
  } catch (const SpecError& e) {
    for (const std::string& m : e.messages()) std::fprintf(stderr, "%s\n", m.c_str());
    const size_t n = e.messages().size();
    throw InputError(opt.spec_path + ": " + std::to_string(n) + (n == 1 ? " problem" : " problems") +
                     " found; the spec is invalid");
  }
  // What `run` reads beyond the spec is read here too, so that validate refuses what run would: the
  // manifold's mesh (an unreadable or huge file) and the crowd on its area (issue 33).
  if (spec.scenario.type == ScenarioKind::manifold) check_surface_crowd_limits(spec, load_spec_surface(spec));
  const std::vector<Condition> conditions = enumerate_conditions(spec);
  const std::vector<Condition> practice = enumerate_practice_conditions(spec);
  check_crowd_size_known(spec, conditions);
  check_crowd_size_known(spec, practice);
  std::vector<Condition> all = conditions;
  all.insert(all.end(), practice.begin(), practice.end());
  read_referenced_files(spec, all);
  print_summary(spec);
  if (!opt.no_table) {
    std::printf("\n");
    print_table(spec, conditions);
    if (!practice.empty()) {
      std::printf("\npractice trials:\n");
      print_table(spec, practice);
    }
  }
  std::printf("\n%zu conditions", conditions.size());
  if (!practice.empty()) std::printf(" (+%zu practice)", practice.size());
  std::printf("\n");
}

}  // namespace

void add_validate_command(Command& root) {
  auto opt = std::make_shared<ValidateOptions>();
  auto* cmd = root.add_subcommand(
      "validate",
      "Check an experiment spec (every key, type, range and referenced file) and print its design: a "
      "summary, the condition table (id, one column per factor, repetition, seed) and the condition count. "
      "Problems are printed as file:line:column: key.path: message; an invalid spec exits with code 2. "
      "Key reference: docs/spec-reference.md");
  cmd->add_option("spec", opt->spec_path, "The experiment spec (YAML)")->required();
  cmd->add_flag("--no-table", opt->no_table, "Print the summary and count only, not the condition table");
  cmd->callback([opt] { run_validate(*opt); });
}

}  // namespace crowdlab::cli::cmd_validate
