// `crowdlab plan SPEC.yaml --emit slurm|parallel|make --out DIR`: hands the conditions to the job
// engines labs already run, instead of a scheduler of our own. Each job is `crowdlab run --shard K/N`;
// a final `crowdlab run --collect` merges and verifies the shards.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "experiments/cli/command_table.hpp"
#include "experiments/cli/pipeline/job_script_text.hpp"
#include "experiments/cli/pipeline/output_folder_lock.hpp"
#include "framework/core/error.hpp"
#include "framework/pipeline/provenance.hpp"
#include "framework/spec/load_experiment_spec.hpp"

namespace crowdlab::cli::cmd_plan {
namespace {
namespace fs = std::filesystem;

struct Options {
  std::string spec, emit, out, results = "results", exe = "crowdlab";
  int shards = 0;
  int cpus = 2;
};

// Per-frame costs for the resource estimate, from `crowdlab bench` on a 2-core x86-64 machine
// (docs/benchmarks.md): correction ~2 ms/step at 60 characters, rendering + encoding ~70 ms/frame at
// 1080p with 60 characters (llvmpipe). Conservative: the estimate is doubled.
constexpr double kCorrectSecondsPerFrame = 0.002;
constexpr double kRenderSecondsPerFrame = 0.07;

/// The job command `crowdlab run SPEC --out RESULTS`, each word quoted by `quote` for the target language.
std::string run_command(const Options& o, const std::string& spec_abs,
                        std::string (*quote)(const std::string&)) {
  return quote(o.exe) + " run " + quote(spec_abs) + " --out " + quote(o.results);
}

void emit(const Options& o) {
  const ExperimentSpec spec = load_experiment_spec(o.spec);
  const size_t conditions = enumerate_conditions(spec).size() + enumerate_practice_conditions(spec).size();
  // Each shard runs at least one condition: more shards would write empty jobs (issue 32: --shards
  // 2147483647 built a script of two billion lines in memory). Refused from the counts, before writing.
  if (o.shards < 0 || static_cast<size_t>(o.shards) > conditions)
    throw InputError(SourceLocation{"", 0, 0, "--shards"},
                     std::to_string(o.shards) + " shards for " + std::to_string(conditions) +
                         " conditions of " + o.spec + "; give 1 to " + std::to_string(conditions) +
                         " (each shard runs at least one condition)");
  const int n = o.shards > 0 ? o.shards : static_cast<int>(std::min<size_t>(conditions, 64));
  const double frames_per_condition = spec.duration_s * spec.fps;
  const double per_shard_s = 2.0 * std::ceil(static_cast<double>(conditions) / n) * frames_per_condition *
                             (kCorrectSecondsPerFrame + kRenderSecondsPerFrame);
  const int minutes = std::max(10, static_cast<int>(std::ceil(per_shard_s / 60.0)) + 5);
  fs::create_directories(o.out);
  const std::string spec_abs = fs::absolute(o.spec).string();
  // Every value below ends up in a script that a shell, make or sbatch reads (job_script_text.hpp).
  require_script_safe(spec_abs, "spec path");
  require_script_safe(o.results, "--results");
  require_script_safe(o.exe, "--crowdlab");
  const std::string run = run_command(o, spec_abs, o.emit == "make" ? make_recipe_quote : shell_quote);
  const std::string collect = run + " --collect";
  fs::path file;
  std::string text;
  if (o.emit == "slurm") {
    file = fs::path(o.out) / "crowdlab.sbatch";
    text = "#!/bin/bash\n# crowdlab: " + std::to_string(conditions) + " conditions of '" +
           comment_text(spec.name) + "' in " + std::to_string(n) + " array tasks. Submit with: sbatch " +
           file.filename().string() +
           "\n# then, after all tasks: sbatch --dependency=afterok:<jobid> --wrap " + shell_quote(collect) +
           "\n" + "#SBATCH --job-name=crowdlab-" + slurm_directive_word(spec.name) + "\n#SBATCH --array=1-" +
           std::to_string(n) + "\n#SBATCH --cpus-per-task=" + std::to_string(o.cpus) +
           "\n#SBATCH --mem=4G\n#SBATCH --time=" + std::to_string(minutes) +
           "\n#SBATCH --output=crowdlab-%A_%a.log\nset -euo pipefail\n" + run +
           " --shard \"${SLURM_ARRAY_TASK_ID}/" + std::to_string(n) + "\"\n";
  } else if (o.emit == "parallel") {
    file = fs::path(o.out) / "crowdlab.parallel";
    text = "";
    for (int k = 1; k <= n; ++k)
      text += run + " --shard " + std::to_string(k) + "/" + std::to_string(n) + "\n";
  } else if (o.emit == "make") {
    file = fs::path(o.out) / "Makefile";
    text = "# crowdlab: run with make -j<jobs> -f " + comment_text(file.string()) + "\nSHARDS :=";
    for (int k = 1; k <= n; ++k) text += " shard-" + std::to_string(k);
    text += "\n.PHONY: all $(SHARDS)\nall: $(SHARDS)\n\t" + collect + "\n";
    for (int k = 1; k <= n; ++k)
      text += "shard-" + std::to_string(k) + ":\n\t" + run + " --shard " + std::to_string(k) + "/" +
              std::to_string(n) + "\n";
  } else {
    throw InputError(SourceLocation{"", 0, 0, "--emit"},
                     "expected slurm, parallel or make, got '" + o.emit + "'");
  }
  write_file_atomic(file, text);
  std::printf("%zu conditions in %d shards (about %d min each): %s\n", conditions, n, minutes,
              file.string().c_str());
  if (o.emit == "parallel")
    std::printf("run: parallel -j %d < %s && %s\n", std::max(1, n), file.string().c_str(), collect.c_str());
}

}  // namespace

void add_plan_command(Command& root) {
  auto o = std::make_shared<Options>();
  auto* cmd = root.add_subcommand(
      "plan", "Write job scripts (Slurm array, GNU parallel, make) that run a spec in shards");
  cmd->add_option("spec", o->spec, "Experiment spec (YAML)")->required()->check(check::existing_file());
  cmd->add_option("--emit", o->emit, "slurm | parallel | make")->required();
  cmd->add_option("--out", o->out, "Folder for the generated script")->required();
  cmd->add_option("--results", o->results, "Output folder the jobs write to")->capture_default_str();
  cmd->add_option("--shards", o->shards, "Number of shards (default: one per condition, at most 64)");
  cmd->add_option("--cpus", o->cpus, "CPUs per Slurm task")->capture_default_str();
  cmd->add_option("--crowdlab", o->exe, "Path of the crowdlab binary on the cluster")->capture_default_str();
  cmd->callback([o] {
    const OutputFolderLock lock(o->out);  // one process per folder (output_folder_lock.hpp)
    emit(*o);
  });
}

}  // namespace crowdlab::cli::cmd_plan
