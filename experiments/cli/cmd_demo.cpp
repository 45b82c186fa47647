// `crowdlab demo [--out DIR]`: the embedded demo experiment end to end: stimuli for every condition,
// a simulated study with 12 observers, and the analysis report. Ends by printing where everything is.
#include <cstdio>
#include <filesystem>
#include <memory>

#include "analysis/study_report.hpp"
#include "crowdlab_embedded_demo.hpp"
#include "experiments/cli/command_registry.hpp"
#include "experiments/cli/pipeline/provenance.hpp"
#include "experiments/cli/pipeline/run_pipeline.hpp"
#include "framework/core/stimulus_manifest.hpp"
#include "framework/spec/load_experiment_spec.hpp"
#include "study_ui/simulate_study.hpp"

namespace crowdlab::cli {
namespace {
namespace fs = std::filesystem;

struct Options {
  std::string out = "demo-out";
  int observers = 12;
  bool force = false;
};

void run_demo(const Options& o) {
  const fs::path dir = fs::absolute(o.out);
  fs::create_directories(dir);
  // The spec is written out first so that every later stage (and the user) reads a real file.
  const fs::path spec_path = dir / "spec.yaml";
  write_file_atomic(spec_path, kEmbeddedDemoSpec);
  const ExperimentSpec spec = load_experiment_spec(spec_path.string());

  RunOptions ro;
  ro.out_dir = dir / "stimuli";
  ro.force = o.force;
  const RunSummary run = run_experiment(spec, ro);

  // The simulated data set is regenerated from its seed each time (simulate_study never overwrites).
  const fs::path study_dir = dir / "study";
  fs::remove_all(study_dir);
  study::SimulateStudyOptions so;
  so.observers = o.observers;
  so.seed = spec.seed;
  so.stimuli_dir = ro.out_dir.string();
  so.out_dir = study_dir.string();
  const std::string responses =
      study::simulate_study(spec, read_manifest(run.manifest.string()), study::ObserverModel{}, so);

  const std::string report =
      analysis::write_study_report(study_dir.string(), spec_path.string(), (dir / "report").string());

  std::printf("\ncrowdlab demo finished (%d conditions; %d stage outputs made, %d reused)\n", run.conditions,
              run.stages_run, run.stages_skipped);
  std::printf("  spec:           %s\n", spec_path.c_str());
  std::printf("  stimuli:        %s (manifest: %s)\n", ro.out_dir.c_str(), run.manifest.c_str());
  std::printf("  contact sheets: %s/crowds/*/*.contact_sheet.png\n", ro.out_dir.c_str());
  std::printf("  responses:      %s (%d simulated observers)\n", responses.c_str(), o.observers);
  std::printf("  report:         %s\n", report.c_str());
}

const CommandRegistration kRegistration([](CLI::App& root) {
  auto o = std::make_shared<Options>();
  auto* cmd = root.add_subcommand(
      "demo", "Run the embedded demo experiment end to end (stimuli, simulated study, report)");
  cmd->add_option("--out", o->out, "Output folder")->capture_default_str();
  cmd->add_option("--observers", o->observers, "Simulated observers")
      ->check(CLI::Range(2, 1000))
      ->capture_default_str();
  cmd->add_flag("--force", o->force, "Re-run every stage even when up to date");
  cmd->callback([o] { run_demo(*o); });
});

}  // namespace
}  // namespace crowdlab::cli
