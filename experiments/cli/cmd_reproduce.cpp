// `crowdlab reproduce gomez2024|hoyet2016 --out DIR [--quick]`: regenerate a paper's quantitative
// results (figures, tables, checks against the paper's values) with the pipeline's own stages.
// The work lives in reproduce/reproduce_<paper>.cpp; each header lists what is reproduced, the sizes
// and the tolerances. Exit code 1 when a result leaves its tolerance (outputs are written first).
#include <memory>

#include "experiments/cli/command_table.hpp"
#include "experiments/cli/pipeline/output_folder_lock.hpp"
#include "experiments/cli/reproduce/reproduce_gomez2024.hpp"
#include "experiments/cli/reproduce/reproduce_hoyet2016.hpp"

namespace crowdlab::cli::cmd_reproduce {
namespace {

Command* add_paper(Command* group, const std::string& name, const std::string& description,
                   std::shared_ptr<ReproduceOptions> o, const std::string& duration_help,
                   const std::string& fps_help) {
  auto* cmd = group->add_subcommand(name, description);
  cmd->add_option("-o,--out", o->out, "Output folder (README.md report, checks.json, figures, tables)")
      ->required();
  cmd->add_flag("--quick", o->quick,
                "Reduced size for CI (see docs/reproductions.md); same tolerances policy");
  cmd->add_option("--duration", o->duration_s, duration_help)->check(check::range(0.1, 60.0));
  cmd->add_option("--fps", o->fps, fps_help)->check(check::range(5.0, 120.0));
  cmd->add_option("--observers", o->observers, "Override the number of simulated observers")
      ->check(check::range(3, 1000));
  cmd->add_flag("--force", o->force, "Recompute every pipeline stage even when up to date");
  return cmd;
}

}  // namespace

void add_reproduce_command(Command& root) {
  auto* group = root.add_subcommand("reproduce", "Regenerate a paper's quantitative results and check them")
                    ->require_subcommand(1);
  auto gomez = std::make_shared<ReproduceOptions>();
  auto* g = add_paper(group, "gomez2024",
                      "Seed 000 (Gómez et al. 2024): Fig. 3 overlap vs density, Fig. 4 damping sweep, timing "
                      "table beside the paper's, and the study analysis on simulated observers",
                      gomez, "Override the clip length of both studies' specs (seconds)",
                      "Override the frame rate of both studies' specs");
  g->add_flag("--skip-timing", gomez->skip_timing, "Leave out the timing table");
  g->callback([gomez] {
    const OutputFolderLock lock(gomez->out);  // one process per folder (output_folder_lock.hpp)
    reproduce_gomez2024(*gomez);
  });
  auto hoyet = std::make_shared<ReproduceOptions>();
  auto* h =
      add_paper(group, "hoyet2016",
                "Seed 001 (Hoyet et al. 2016): Fig. 3 volume vs distance per shoulder condition, Table 1 "
                "D_crit/V_crit recovered from simulated observers, Table 2 collisions per scenario x density",
                hoyet, "Override the length of the Table 2 flows (seconds)",
                "Override the frame rate of the pair clips (Fig. 3, Table 1)");
  h->add_option("--repetitions", hoyet->repetitions, "Override the repetitions of each pair condition")
      ->check(check::range(1, 32));
  h->callback([hoyet] {
    const OutputFolderLock lock(hoyet->out);
    reproduce_hoyet2016(*hoyet);
  });
}

}  // namespace crowdlab::cli::cmd_reproduce
