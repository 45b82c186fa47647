// `crowdlab study`, `crowdlab simulate-study`, `crowdlab power`: study sessions (window, scripted or
// simulated participant), synthetic data sets and power by simulated studies. Logic lives in study_ui/.
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "experiments/cli/command_estimates.hpp"
#include "experiments/cli/command_table.hpp"
#include "experiments/cli/pipeline/output_folder_lock.hpp"
#include "framework/core/error.hpp"
#include "framework/core/seed.hpp"
#include "framework/core/stimulus_manifest.hpp"
#include "framework/spec/load_experiment_spec.hpp"
#include "study_ui/estimate_power.hpp"
#include "study_ui/run_session.hpp"
#include "study_ui/scripted_presenter.hpp"
#include "study_ui/simulate_study.hpp"
#include "study_ui/simulated_presenter.hpp"
#include "study_ui/window_presenter.hpp"

namespace crowdlab::cli::cmd_study {
namespace {

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, sep))
    if (!item.empty()) out.push_back(item);
  return out;
}

/// "default" or "key=value,key=value" (ObserverModel::set keys).
study::ObserverModel observer_model(const std::string& text) {
  study::ObserverModel model;
  if (text.empty() || text == "default") return model;
  for (const auto& assignment : split(text, ',')) model.set(assignment);
  return model;
}

StimulusManifest load_manifest(const std::string& stimuli_dir) {
  const std::string path = (std::filesystem::path(stimuli_dir) / "manifest.csv").string();
  if (!std::filesystem::is_regular_file(path))
    throw InputError(SourceLocation{"", 0, 0, "--stimuli"},
                     path + ": no stimulus manifest (run `crowdlab run` first)");
  return read_manifest(path);
}

struct StudyArgs {
  std::string spec, participant, stimuli, out, responses, simulate, windowed, snapshot_dir;
  bool resume = false, require_fullscreen = false;
  int delay_ms = 0;
  std::uint64_t seed = 0;
  bool seed_given = false;
};

void run_study(const StudyArgs& a) {
  const ExperimentSpec spec = load_experiment_spec(a.spec);
  const StimulusManifest manifest = load_manifest(a.stimuli);
  study::SessionOptions opt;
  opt.participant = a.participant;
  opt.stimuli_dir = a.stimuli;
  // Simulated answers default to their own folder, so that they never sit beside a real study's.
  const char* default_out = a.simulate.empty() ? "responses" : "responses-simulated";
  opt.out_dir = a.out.empty() ? (std::filesystem::path(a.stimuli) / default_out).string() : a.out;
  opt.simulated = !a.simulate.empty();
  opt.resume = a.resume;
  // Everything the session will check, before any window opens (a participant never sees a window
  // that then closes on an experimenter's mistake).
  study::check_session_inputs(spec, manifest, opt);
  opt.verify_files = false;  // verified just now
  std::unique_ptr<study::Presenter> presenter;
  if (!a.responses.empty()) {
    auto scripted = std::make_unique<study::ScriptedPresenter>(a.responses, a.delay_ms);
    scripted->check(manifest, study::resolve_questions(spec.protocol));
    presenter = std::move(scripted);
    opt.presenter_name = "scripted:" + a.responses;
  } else if (!a.simulate.empty()) {
    const std::uint64_t seed = a.seed_given ? a.seed : derive_seed(spec.seed, "observer:" + a.participant);
    presenter = std::make_unique<study::SimulatedPresenter>(observer_model(a.simulate), seed);
    opt.presenter_name = "simulated:" + a.simulate;
  } else {
    study::WindowOptions w;
    if (!a.windowed.empty()) {
      int width = 0, height = 0;
      if (std::sscanf(a.windowed.c_str(), "%dx%d", &width, &height) != 2 || width < 320 || height < 240)
        throw InputError(SourceLocation{"", 0, 0, "--windowed"},
                         "expected WxH with W >= 320, H >= 240, got '" + a.windowed + "'");
      w.fullscreen = false;
      w.width = width;
      w.height = height;
    }
    w.snapshot_dir = a.snapshot_dir;
    w.require_fullscreen = a.require_fullscreen;
    presenter = std::make_unique<study::WindowPresenter>(w);
    opt.presenter_name = "window";
  }
  const study::SessionResult r = study::run_session(spec, manifest, opt, *presenter);
  if (r.declined) {  // a legitimate end of a session, not a failure
    std::printf("participant %s declined to take part: no trial shown (status \"declined\" in %s)\n",
                a.participant.c_str(), r.json_path.c_str());
    return;
  }
  std::printf(
      "participant %s: %d/%d trials done (%d this run)%s, %ld frame(s) dropped\nresponses: %s\nmetadata:  "
      "%s\n",
      a.participant.c_str(), r.trials_already_done + r.trials_done_now, r.trials_total, r.trials_done_now,
      r.complete ? ", complete" : (r.aborted ? ", aborted (continue with --resume)" : ""), r.frames_dropped,
      r.csv_path.c_str(), r.json_path.c_str());
  if (r.aborted) throw RuntimeError("session aborted by the participant; resume with --resume");
}

}  // namespace

void add_study_command(Command& root) {
  auto a = std::make_shared<StudyArgs>();
  auto* cmd = root.add_subcommand(
      "study",
      "Run a study session for one participant: full-screen window by default, or headless with --responses "
      "(scripted replay) or --simulate (simulated observer). Every trial's answers are fsync'd to "
      "OUT/<participant>.csv before the next trial; metadata goes to OUT/<participant>.json.");
  cmd->add_option("spec", a->spec, "Experiment spec (YAML)")->required()->check(check::existing_file());
  cmd->add_option("--participant", a->participant, "Participant id (A-Z a-z 0-9 _ -), e.g. P07")->required();
  cmd->add_option("--stimuli", a->stimuli, "Stimulus folder holding manifest.csv")
      ->required()
      ->check(check::existing_directory());
  cmd->add_option(
      "--out", a->out,
      "Response folder (default: STIMULI/responses; with --simulate: STIMULI/responses-simulated)");
  cmd->add_flag(
      "--resume", a->resume,
      "Continue an interrupted session at the first unanswered trial (a used id is refused without it)");
  auto* responses =
      cmd->add_option("--responses", a->responses,
                      "Headless: replay answers from a CSV with columns stimulus,question,response[,rt_ms]")
          ->check(check::existing_file());
  cmd->add_option("--response-delay-ms", a->delay_ms,
                  "With --responses: wait this long in every trial (testing)");
  auto* simulate =
      cmd->add_option("--simulate", a->simulate,
                      "Headless: answer as a simulated observer: 'default' or key=value,... "
                      "(e.g. lapse=0.05,effect.method.ours=1.0; see study_ui/simulated_observer.hpp)");
  responses->excludes(simulate);
  cmd->add_option("--seed", a->seed,
                  "Simulated observer seed (default: derived from the spec seed and participant)")
      ->each([a](const std::string&) { a->seed_given = true; });
  auto* windowed = cmd->add_option("--windowed", a->windowed,
                                   "Window of WxH pixels instead of full screen (testing), e.g. 1280x720");
  cmd->add_flag("--require-fullscreen", a->require_fullscreen,
                "Fail (exit 1) when the window cannot cover the whole screen, instead of falling back to a "
                "1280x720 window")
      ->excludes(windowed)
      ->excludes(responses)
      ->excludes(simulate);
  cmd->add_option("--snapshot-dir", a->snapshot_dir, "Save the window's rendered screens as PNGs here");
  cmd->callback([a] { run_study(*a); });
}

namespace {

struct SimArgs {
  std::string spec, stimuli, out, observer = "default";
  int observers = 30;
  std::uint64_t seed = 1;
};

}  // namespace

void add_simulate_study_command(Command& root) {
  auto a = std::make_shared<SimArgs>();
  auto* cmd = root.add_subcommand(
      "simulate-study",
      "Write a complete synthetic data set (S001.csv/.json ... and a merged responses.csv) "
      "in the format of real sessions, answered by simulated observers");
  cmd->add_option("spec", a->spec, "Experiment spec (YAML)")->required()->check(check::existing_file());
  cmd->add_option("--stimuli", a->stimuli, "Stimulus folder holding manifest.csv")
      ->required()
      ->check(check::existing_directory());
  cmd->add_option("--observers", a->observers, "Number of simulated participants")->capture_default_str();
  cmd->add_option("--out", a->out, "Output folder (must not hold a data set yet)")->required();
  cmd->add_option("--seed", a->seed, "Seed of the synthetic data set")->capture_default_str();
  cmd->add_option("--observer", a->observer, "Observer model: 'default' or key=value,...")
      ->capture_default_str();
  cmd->callback([a] {
    const OutputFolderLock lock(a->out);  // one process per folder (output_folder_lock.hpp)
    const ExperimentSpec spec = load_experiment_spec(a->spec);
    const StimulusManifest manifest = load_manifest(a->stimuli);
    study::SimulateStudyOptions opt;
    opt.observers = a->observers;
    opt.seed = a->seed;
    opt.stimuli_dir = a->stimuli;
    opt.out_dir = a->out;
    if (a->observers >= 1)  // fewer is refused by simulate_study
      announce_estimate("simulating observers",
                        simulate_study_estimate(a->observers, static_cast<double>(manifest.entries.size()),
                                                static_cast<double>(spec.protocol.questions.size())));
    const std::string merged = study::simulate_study(spec, manifest, observer_model(a->observer), opt);
    std::printf("%d simulated participant(s) written to %s\nmerged responses: %s\n", a->observers,
                a->out.c_str(), merged.c_str());
  });
}

namespace {

/// Test stimuli at either level of the contrast: the ones every simulated observer of `power` answers.
double contrast_stimuli(const StimulusManifest& manifest, const std::string& factor,
                        const std::vector<std::string>& levels) {
  return static_cast<double>(std::ranges::count_if(manifest.entries, [&](const StimulusEntry& e) {
    const auto it = e.factors.find(factor);
    return !e.practice && it != e.factors.end() && std::ranges::find(levels, it->second) != levels.end();
  }));
}

struct PowerArgs {
  std::string spec, stimuli, contrast, dv, n = "10,20,30", observer = "default";
  double effect = 0.8, alpha = 0.05;
  int simulations = 200;
  std::uint64_t seed = 1;
  bool json = false;
};

}  // namespace

void add_power_command(Command& root) {
  auto a = std::make_shared<PowerArgs>();
  auto* cmd = root.add_subcommand("power",
                                  "Estimate the power to detect an effect with n participants, by simulated "
                                  "studies: simulated observers answer "
                                  "every stimulus; a paired t-test (level B vs level A of --contrast, on "
                                  "--dv) per simulated study. A minimal "
                                  "planning tool: the full analysis is `crowdlab analyze`.");
  cmd->add_option("spec", a->spec, "Experiment spec (YAML)")->required()->check(check::existing_file());
  cmd->add_option("--stimuli", a->stimuli, "Stimulus folder holding manifest.csv")
      ->required()
      ->check(check::existing_directory());
  cmd->add_option("--contrast", a->contrast,
                  "FACTOR:A,B: compare level B against level A (default method:baseline,ours)");
  cmd->add_option(
         "--effect", a->effect,
         "Simulated effect of level B: shift of the observers' latent realism (logit units; 0.8 is the "
         "default observer model's method effect). The stimuli's metrics add their own difference through "
         "the overlap_weight and collision_weight terms; --observer overlap_weight=0,collision_weight=0 "
         "simulates --effect alone")
      ->capture_default_str();
  cmd->add_option("--dv", a->dv,
                  "Question or composite id to test (default: first composite, else first question)");
  cmd->add_option("--n", a->n, "Comma-separated numbers of participants")->capture_default_str();
  cmd->add_option("--simulations", a->simulations, "Simulated studies per n")->capture_default_str();
  cmd->add_option("--alpha", a->alpha, "Significance level")->capture_default_str();
  cmd->add_option("--seed", a->seed, "Seed")->capture_default_str();
  cmd->add_option("--observer", a->observer, "Observer model: 'default' or key=value,...")
      ->capture_default_str();
  cmd->add_flag("--json", a->json, "Print one JSON object");
  cmd->callback([a] {
    const ExperimentSpec spec = load_experiment_spec(a->spec);
    const StimulusManifest manifest = load_manifest(a->stimuli);
    study::PowerOptions opt;
    const std::string contrast = a->contrast.empty() ? "method:baseline,ours" : a->contrast;
    const size_t colon = contrast.find(':');
    const auto levels =
        colon == std::string::npos ? std::vector<std::string>{} : split(contrast.substr(colon + 1), ',');
    if (colon == std::string::npos || colon == 0 || levels.size() != 2)
      throw InputError(SourceLocation{"", 0, 0, "--contrast"}, "expected FACTOR:A,B, got '" + contrast + "'");
    opt.factor = contrast.substr(0, colon);
    opt.level_a = levels[0];
    opt.level_b = levels[1];
    opt.dv = a->dv;
    opt.simulations = a->simulations;
    opt.alpha = a->alpha;
    opt.seed = a->seed;
    opt.sample_sizes.clear();
    for (const auto& s : split(a->n, ',')) {
      // The whole text: stoi read "10.5" and "10abc" as 10, silently (issue 33).
      try {
        size_t used = 0;
        const int n = std::stoi(s, &used);
        if (used != s.size()) throw InputError("");
        opt.sample_sizes.push_back(n);
      } catch (const std::exception&) {
        throw InputError(SourceLocation{"", 0, 0, "--n"}, "not an integer: '" + s + "'");
      }
    }
    study::ObserverModel model = observer_model(a->observer);
    model.level_effects.erase("method=ours");
    model.level_effects[opt.factor + "=" + opt.level_b] = a->effect;
    if (opt.simulations >= 1 && std::ranges::all_of(opt.sample_sizes, [](int n) { return n >= 2; }))
      announce_estimate("power",
                        power_estimate(opt.sample_sizes, opt.simulations,
                                       contrast_stimuli(manifest, opt.factor, {levels[0], levels[1]})));
    const auto rows = study::estimate_power(spec, manifest, model, opt);
    if (a->json) {
      nlohmann::json j = {{"factor", opt.factor},
                          {"level_a", opt.level_a},
                          {"level_b", opt.level_b},
                          {"effect", a->effect},
                          {"alpha", opt.alpha},
                          {"simulations", opt.simulations},
                          {"test", "paired t-test (two-sided)"},
                          {"rows", nlohmann::json::array()}};
      for (const auto& r : rows)
        j["rows"].push_back({{"n", r.n},
                             {"power", r.power},
                             {"mean_difference", r.mean_difference},
                             {"mean_cohens_dz", r.mean_cohens_dz}});
      std::printf("%s\n", j.dump().c_str());
      return;
    }
    std::printf(
        "power of a paired t-test, %s: %s vs %s, effect %.3g, alpha %.3g, %d simulated studies per n\n",
        opt.factor.c_str(), opt.level_b.c_str(), opt.level_a.c_str(), a->effect, opt.alpha, opt.simulations);
    std::printf("%6s %8s %16s %10s\n", "n", "power", "mean diff (B-A)", "mean d_z");
    for (const auto& r : rows)
      std::printf("%6d %8.3f %16.3f %10.2f\n", r.n, r.power, r.mean_difference, r.mean_cohens_dz);
  });
}

}  // namespace crowdlab::cli::cmd_study
