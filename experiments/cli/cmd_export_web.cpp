// `crowdlab export-web`: a spec's study as a static jsPsych web experiment (and a JATOS archive).
// Logic lives in study_ui/web_export.*; see docs/online.md.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>

#include "crowdlab_web_dirs.hpp"
#include "experiments/cli/command_table.hpp"
#include "framework/core/error.hpp"
#include "framework/core/stimulus_manifest.hpp"
#include "framework/spec/load_experiment_spec.hpp"
#include "study_ui/web_export.hpp"

namespace crowdlab::cli::cmd_export_web {
namespace {

struct ExportWebArgs {
  std::string spec, stimuli, out, jatos, participants = "24", jspsych = CROWDLAB_WEB_MODULES_DIR;
};

/// "N" (ids P01..PN) or a comma-separated list of ids.
std::vector<std::string> participant_ids(const std::string& text) {
  if (!text.empty() && text.find_first_not_of("0123456789") == std::string::npos) {
    if (text.size() > 6)
      throw InputError(SourceLocation{"", 0, 0, "--participants"}, "too many participants: " + text);
    return study::numbered_participant_ids(std::stoi(text));
  }
  std::vector<std::string> ids;
  std::stringstream ss(text);
  std::string id;
  while (std::getline(ss, id, ','))
    if (!id.empty()) ids.push_back(id);
  if (ids.empty())
    throw InputError(SourceLocation{"", 0, 0, "--participants"},
                     "expected N or a list of ids, got '" + text + "'");
  return ids;
}

}  // namespace

void add_export_web_command(Command& root) {
  auto a = std::make_shared<ExportWebArgs>();
  auto* cmd = root.add_subcommand(
      "export-web",
      "Write the spec's study as a static jsPsych web experiment (index.html, jsPsych, clips, timeline.json) "
      "that runs the same protocol and, per participant id, the same trial order as `crowdlab study`; "
      "optionally also a JATOS study archive. See docs/online.md.");
  cmd->add_option("spec", a->spec, "Experiment spec (YAML)")->required()->check(check::existing_file());
  cmd->add_option("--stimuli", a->stimuli, "Stimulus folder holding manifest.csv")
      ->required()
      ->check(check::existing_directory());
  cmd->add_option("--out", a->out, "Web study folder to write (absent or empty)")->required();
  cmd->add_option("--jatos", a->jatos, "Also write a JATOS study archive (.jzip) here");
  cmd->add_option("--participants", a->participants,
                  "Ids whose trial orders are embedded: N (P01..PN) or a comma-separated list; other ids "
                  "(e.g. PROLIFIC_PID) run the order of a hashed embedded id")
      ->capture_default_str();
  // No capture_default_str: the default is this build's folder, and docs/cli.md must not name one.
  cmd->add_option(
      "--jspsych", a->jspsych,
      "node_modules folder holding jspsych and @jspsych/plugin-* (default: BUILD/web/node_modules, "
      "installed by make web-deps)");
  cmd->callback([a] {
    const ExperimentSpec spec = load_experiment_spec(a->spec);
    const std::string manifest_path = (std::filesystem::path(a->stimuli) / "manifest.csv").string();
    if (!std::filesystem::is_regular_file(manifest_path))
      throw InputError(SourceLocation{"", 0, 0, "--stimuli"},
                       manifest_path + ": no stimulus manifest (run `crowdlab run` first)");
    study::WebExportOptions opt;
    opt.stimuli_dir = a->stimuli;
    opt.out_dir = a->out;
    opt.jatos_path = a->jatos;
    opt.participants = participant_ids(a->participants);
    opt.web_source_dir = CROWDLAB_WEB_SOURCE_DIR;
    opt.node_modules_dir = a->jspsych;
    const study::WebExportResult r = study::export_web(spec, read_manifest(manifest_path), opt);
    std::printf("web study: %s (%d files, %d clips, %.1f MB), %zu participant order(s) embedded\n",
                a->out.c_str(), r.files, r.clips, static_cast<double>(r.bytes) / 1e6,
                opt.participants.size());
    std::printf("pilot it: open %s/index.html?participant=%s through a web server (see docs/online.md)\n",
                a->out.c_str(), opt.participants.front().c_str());
    if (!a->jatos.empty())
      std::printf("JATOS archive: %s (study assets folder %s)\n", a->jatos.c_str(), r.jatos_dir.c_str());
  });
}

}  // namespace crowdlab::cli::cmd_export_web
