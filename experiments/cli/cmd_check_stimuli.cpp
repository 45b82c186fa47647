// `crowdlab check-stimuli DIR`: the stimulus check of a finished run (manifest.csv, judged by the run's
// copy of its spec, DIR/spec.yaml) as a table; stimuli/stimulus_check.hpp defines the measures.
#include <cstdio>
#include <filesystem>
#include <memory>

#include "experiments/cli/command_table.hpp"
#include "experiments/cli/stimulus_check_table.hpp"
#include "framework/core/error.hpp"
#include "framework/spec/load_experiment_spec.hpp"

namespace crowdlab::cli::cmd_check_stimuli {
namespace {

struct Options {
  std::string dir;
  std::string spec;
  bool strict = false;
};

}  // namespace

void add_check_stimuli_command(Command& root) {
  auto o = std::make_shared<Options>();
  auto* cmd = root.add_subcommand(
      "check-stimuli",
      "Print the stimulus check of a finished run (crowd in frame, character height, overlap visibility, "
      "loop seam per clip), judged by the thresholds of the run's spec (render.check).");
  cmd->add_option("dir", o->dir, "Output folder of `crowdlab run` (holds manifest.csv and spec.yaml)")
      ->required()
      ->check(check::existing_directory());
  cmd->add_option("--spec", o->spec,
                  "Judge by this spec instead of DIR/spec.yaml (e.g. when the copy's relative paths do not "
                  "resolve from DIR)")
      ->check(check::existing_file());
  cmd->add_flag("--strict", o->strict, "Exit with code 1 when any clip misses a threshold");
  cmd->callback([o] {
    namespace fs = std::filesystem;
    const fs::path manifest = fs::path(o->dir) / "manifest.csv";
    const fs::path spec_path = o->spec.empty() ? fs::path(o->dir) / "spec.yaml" : fs::path(o->spec);
    if (!fs::exists(manifest)) throw InputError(manifest.string() + ": no manifest (is this a run folder?)");
    if (!fs::exists(spec_path))
      throw InputError(spec_path.string() + ": no spec copy (is this a run folder?)");
    const StimulusCheckTable t =
        stimulus_check_table(read_manifest(manifest.string()), load_experiment_spec(spec_path.string()));
    std::printf("%s\n%d clip(s): %d outside render.check, %d not measured\n", t.markdown.c_str(), t.clips,
                t.failed, t.unmeasured);
    if (o->strict && t.failed > 0)
      throw RuntimeError("check-stimuli --strict: " + std::to_string(t.failed) +
                         " clip(s) outside render.check");
  });
}

}  // namespace crowdlab::cli::cmd_check_stimuli
