#include "experiments/cli/reproduce/reproduce_common.hpp"

#include <fstream>

#include "analysis/study_report.hpp"
#include "experiments/cli/pipeline/render_stages.hpp"
#include "experiments/cli/reproduce/spec_variant.hpp"
#include "framework/core/error.hpp"
#include "framework/spec/load_experiment_spec.hpp"
#include "study_ui/simulate_study.hpp"

namespace crowdlab::cli {
namespace fs = std::filesystem;

SpecRun run_spec_variant(const std::string& yaml_text, const fs::path& dir, const std::string& name,
                         bool force, const std::function<void(YAML::Node& root)>& edit, bool mesh_measures,
                         bool stimulus_check) {
  SpecRun r;
  r.spec_path = dir / "specs" / (name + ".yaml");
  r.spec = write_spec_variant(yaml_text, r.spec_path, [&](YAML::Node& root) {
    root["outputs"]["video"] = false;
    root["outputs"]["contact_sheet"] = false;
    root["outputs"]["metrics"] = true;
    if (stimulus_check) root["render"]["check"]["overlap_every_frames"] = 0;
    edit(root);
  });
  r.run_dir = dir / name;
  RunOptions ro;
  ro.out_dir = r.run_dir;
  ro.force = force;
  ro.mesh_measures = mesh_measures;
  const RunSummary summary = run_with_stimuli(r.spec, ro, false, stimulus_check);
  r.manifest = read_manifest(summary.manifest.string());
  return r;
}

nlohmann::json entry_metrics(const SpecRun& run, const StimulusEntry& entry) {
  const fs::path path = run.run_dir / "conditions" / entry.id / "metrics.json";
  std::ifstream in(path);
  if (!in) throw RuntimeError("missing metrics of condition " + entry.id + ": " + path.string());
  return nlohmann::json::parse(in);
}

std::string simulate_study_and_report(const SpecRun& run, const study::ObserverModel& model, int observers,
                                      std::uint64_t seed, const fs::path& study_dir,
                                      const fs::path& report_dir) {
  fs::remove_all(study_dir);  // a simulated data set is regenerated from its seed, never appended to
  study::SimulateStudyOptions so;
  so.observers = observers;
  so.seed = seed;
  so.stimuli_dir = run.run_dir.string();
  so.out_dir = study_dir.string();
  so.verify_files = false;  // no clips were rendered: observers answer from the metrics
  study::simulate_study(run.spec, run.manifest, model, so);
  return analysis::write_study_report(study_dir.string(), run.spec_path.string(), report_dir.string());
}

}  // namespace crowdlab::cli
