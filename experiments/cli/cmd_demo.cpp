// `crowdlab demo [--out DIR]`: the embedded demo experiment end to end: stimuli for every condition,
// a simulated study with 12 observers, and the analysis report. Ends by printing where everything is.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <vector>

#include "analysis/study_report.hpp"
#include "crowdlab_embedded_demo.hpp"
#include "experiments/cli/command_table.hpp"
#include "experiments/cli/pipeline/output_folder_lock.hpp"
#include "experiments/cli/pipeline/render_stages.hpp"
#include "framework/core/stimulus_manifest.hpp"
#include "framework/pipeline/provenance.hpp"
#include "framework/spec/load_experiment_spec.hpp"
#include "study_ui/simulate_study.hpp"

namespace crowdlab::cli::cmd_demo {
namespace {
namespace fs = std::filesystem;

struct Options {
  std::string out = "demo-out";
  int observers = 12;
  bool force = false;
};

/// Appends the stimuli's contact sheets (one per crowd and method, written by the stimuli stage) to the
/// report, copied beside it so that the report folder is self-contained. Returns how many were added.
int append_contact_sheets(const fs::path& report_md, const fs::path& stimuli_dir) {
  std::vector<fs::path> sheets;
  for (const auto& entry : fs::recursive_directory_iterator(stimuli_dir / "crowds"))
    if (entry.is_regular_file() && entry.path().string().ends_with(".contact_sheet.png"))
      sheets.push_back(entry.path());
  std::sort(sheets.begin(), sheets.end());
  if (sheets.empty()) return 0;
  const fs::path figures = report_md.parent_path() / "figures" / "stimuli";
  fs::create_directories(figures);
  std::string md =
      "\n## Stimuli: contact sheets\n\nOne frame (mid-clip) of every crowd from the four viewpoints "
      "V1 front, V2 upper-front, V3 front-side, V4 overhead, per method.\n\n";
  for (const fs::path& sheet : sheets) {
    const std::string crowd = sheet.parent_path().filename().string();
    const std::string method = sheet.filename().string().substr(0, sheet.filename().string().find('.'));
    const std::string name = crowd + "_" + method + ".png";
    fs::copy_file(sheet, figures / name, fs::copy_options::overwrite_existing);
    md += "**" + crowd + ", " + method + "**\n\n![" + crowd + " " + method + "](figures/stimuli/" + name +
          ")\n\n";
  }
  std::ofstream(report_md, std::ios::app) << md;
  return static_cast<int>(sheets.size());
}

void run_demo(const Options& o) {
  const fs::path dir = fs::absolute(o.out);
  // One process per folder (output_folder_lock.hpp); the stimuli folder is also a `run --out`.
  const OutputFolderLock lock(dir), stimuli_lock(dir / "stimuli");
  // The spec is written out first so that every later stage (and the user) reads a real file.
  const fs::path spec_path = dir / "spec.yaml";
  write_file_atomic(spec_path, kEmbeddedDemoSpec);
  const ExperimentSpec spec = load_experiment_spec(spec_path.string());

  RunOptions ro;
  ro.out_dir = dir / "stimuli";
  ro.force = o.force;
  const RunSummary run = run_with_stimuli(spec, ro);

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
  const int sheets = append_contact_sheets(report, ro.out_dir);

  std::printf("\ncrowdlab demo finished (%d conditions; %d stage outputs made, %d reused)\n", run.conditions,
              run.stages_run, run.stages_skipped);
  std::printf("  spec:           %s\n", spec_path.c_str());
  std::printf("  stimuli:        %s (manifest: %s)\n", ro.out_dir.c_str(), run.manifest.c_str());
  std::printf("  contact sheets: %s/crowds/*/*.contact_sheet.png (%d, also in the report)\n",
              ro.out_dir.c_str(), sheets);
  std::printf("  responses:      %s (%d simulated observers)\n", responses.c_str(), o.observers);
  std::printf("  report:         %s\n", report.c_str());
}

}  // namespace

void add_demo_command(Command& root) {
  auto o = std::make_shared<Options>();
  auto* cmd = root.add_subcommand(
      "demo", "Run the embedded demo experiment end to end (stimuli, simulated study, report)");
  cmd->add_option("--out", o->out, "Output folder")->capture_default_str();
  cmd->add_option("--observers", o->observers, "Simulated observers")
      ->check(check::range(2, 1000))
      ->capture_default_str();
  cmd->add_flag("--force", o->force, "Re-run every stage even when up to date");
  cmd->callback([o] { run_demo(*o); });
}

}  // namespace crowdlab::cli::cmd_demo
