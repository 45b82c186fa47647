// `crowdlab run SPEC.yaml --out DIR`: every stage for every condition, resumable and incremental.
#include <spdlog/spdlog.h>

#include <cstdio>
#include <memory>

#include "experiments/cli/command_table.hpp"
#include "experiments/cli/pipeline/collect.hpp"
#include "experiments/cli/pipeline/output_folder_lock.hpp"
#include "experiments/cli/pipeline/render_stages.hpp"
#include "framework/spec/load_experiment_spec.hpp"

namespace crowdlab::cli::cmd_run {
namespace {

struct Options {
  std::string spec;
  std::string out;
  std::string shard = "1/1";
  std::string condition;
  bool force = false;
  bool collect = false;
  bool strict = false;
  bool check_only = false;
};

}  // namespace

void add_run_command(Command& root) {
  auto o = std::make_shared<Options>();
  auto* cmd = root.add_subcommand(
      "run",
      "Run every stage (crowd, animation, correction, metrics, stimuli) for every condition of a spec. "
      "Resumable: outputs whose inputs did not change are kept (see DIR/**/*.prov.json).");
  cmd->add_option("spec", o->spec, "Experiment spec (YAML)")->required()->check(check::existing_file());
  cmd->add_option("--out", o->out, "Output folder")->required();
  cmd->add_option("--shard", o->shard,
                  "Run only slice K of N (K/N): crowd group i (all conditions showing one crowd) belongs to "
                  "shard (i mod N) + 1")
      ->capture_default_str();
  cmd->add_option("--condition", o->condition, "Run only the condition with this id");
  cmd->add_flag("--force", o->force, "Re-run every stage even when its outputs are up to date");
  cmd->add_flag(
      "--strict", o->strict,
      "Fail (exit 1, after writing every output) when a clip's stimulus check is outside the spec's "
      "render.check thresholds; without it such clips are warnings");
  cmd->add_flag("--check-only", o->check_only,
                "Measure every clip's stimulus check (the numbers a rendered run writes: crowd in frame, "
                "character height, overlap visibility from every Nth frame drawn in overlap mode, loop seam) "
                "into DIR/conditions/ID/stimulus_check.json and manifest.csv, without drawing or encoding "
                "the clips: minutes where 1080p clips take hours. `check-stimuli DIR` prints the table");
  cmd->add_flag(
      "--collect", o->collect,
      "Merge the shard manifests and provenance records of DIR, verifying every condition is present once");
  cmd->callback([o] {
    const ExperimentSpec spec = load_experiment_spec(o->spec);
    const Shard shard = parse_shard(o->shard);
    // One run (or one shard of a sharded run) per output folder at a time (output_folder_lock.hpp).
    const OutputFolderLock lock(o->out, o->collect ? 1 : shard.index, o->collect ? 1 : shard.count);
    if (o->collect) {
      const CollectSummary c = collect_shards(spec, o->out);
      std::printf(
          "collected %d shard manifest(s): %d stimuli, %d provenance records\nmanifest: %s/manifest.csv\n",
          c.shards, c.entries, c.provenance_records, o->out.c_str());
      return;
    }
    RunOptions ro;
    ro.out_dir = o->out;
    ro.force = o->force;
    ro.shard = shard;
    ro.only = o->condition;
    const RunSummary s = run_with_stimuli(spec, ro, o->strict, o->check_only);
    std::printf("%d conditions: %d stage outputs made, %d up to date\nmanifest: %s\n", s.conditions,
                s.stages_run, s.stages_skipped, s.manifest.string().c_str());
  });
}

}  // namespace crowdlab::cli::cmd_run
