// `crowdlab import-web`: a web study's results as native per-participant tidy CSVs.
// Logic lives in study_ui/web_import.*; see docs/online.md.
#include <cstdio>
#include <filesystem>
#include <memory>

#include "experiments/cli/command_table.hpp"
#include "experiments/cli/pipeline/output_folder_lock.hpp"
#include "framework/core/error.hpp"
#include "framework/core/stimulus_manifest.hpp"
#include "framework/spec/load_experiment_spec.hpp"
#include "study_ui/web_import.hpp"

namespace crowdlab::cli::cmd_import_web {
namespace {

struct ImportWebArgs {
  std::vector<std::string> results;
  std::string spec, stimuli, out;
  double max_file_mb = 256;
  bool strict = false;
};

}  // namespace

void add_import_web_command(Command& root) {
  auto a = std::make_shared<ImportWebArgs>();
  auto* cmd = root.add_subcommand(
      "import-web",
      "Read a web study's results (JATOS result data, the participant's download or a localStorage dump, "
      "jsPsych JSON or CSV) and write the same per-participant tidy CSVs as `crowdlab study`, after checking "
      "the "
      "spec hash, the stimulus hashes and the trial orders. Every participant whose data pass is imported; "
      "the others are listed by file and reason (exit code 2 only when none passes, or with --strict). "
      "See docs/online.md.");
  cmd->add_option("results", a->results,
                  "Result files, or folders searched for *.json, *.jsonl, *.txt, *.csv (jsPsych CSV)")
      ->required();
  cmd->add_option("--spec", a->spec, "The experiment spec (YAML) the web study was exported from")
      ->required()
      ->check(check::existing_file());
  cmd->add_option("--stimuli", a->stimuli, "Stimulus folder holding manifest.csv (the one exported)")
      ->required()
      ->check(check::existing_directory());
  cmd->add_option("--out", a->out, "Response folder for P.csv / P.json (analyze report reads it)")
      ->required();
  cmd->add_option("--max-file-mb", a->max_file_mb,
                  "Result files larger than this (MiB) are refused before they are read")
      ->check(check::range(1.0, 1048576.0))
      ->capture_default_str();
  cmd->add_flag("--strict", a->strict, "Import nothing when any input has a problem");
  cmd->callback([a] {
    const ExperimentSpec spec = load_experiment_spec(a->spec);
    const std::string manifest_path = (std::filesystem::path(a->stimuli) / "manifest.csv").string();
    if (!std::filesystem::is_regular_file(manifest_path))
      throw InputError(SourceLocation{"", 0, 0, "--stimuli"}, manifest_path + ": no stimulus manifest");
    const StimulusManifest manifest = read_manifest(manifest_path);
    study::WebImportOptions opt;
    opt.out_dir = a->out;
    opt.stimuli_dir = a->stimuli;
    opt.max_file_bytes = static_cast<std::uintmax_t>(a->max_file_mb * 1048576.0);
    opt.strict = a->strict;
    // Every check first, without touching --out: a refused input writes nothing (no folder, no lock).
    opt.dry_run = true;
    study::import_web(spec, manifest, a->results, opt);
    // Imports merge into the folder (check, then write): one process per folder (output_folder_lock.hpp);
    // the checks run again under the lock, against the folder as it is now.
    const OutputFolderLock lock(a->out);
    opt.dry_run = false;
    const study::WebImportResult r = study::import_web(spec, manifest, a->results, opt);
    for (const std::string& problem : r.problems) std::fprintf(stderr, "not imported: %s\n", problem.c_str());
    std::printf(
        "%d record(s) from %d file(s), %d identical duplicate(s) merged\n%d participant(s), %d complete, %d "
        "declined, %d already imported, %zu input problem(s)\nresponses: %s\n",
        r.records, r.files, r.duplicates_merged, r.participants, r.complete, r.declined, r.already_imported,
        r.problems.size(), a->out.c_str());
  });
}

}  // namespace crowdlab::cli::cmd_import_web
