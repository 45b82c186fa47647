// `crowdlab experiment damping --out DIR`: seed 000 Fig. 4, the recovery of a shoved character for
// several values of the Eq. 4 damping d. Writes DIR/damping.csv (columns damping,time_s,position_m,
// target_m), DIR/damping_summary.csv (damping,rms_deviation_m,max_deviation_m,overshoot_m,
// final_deviation_m) and the figure DIR/damping.png|svg (pelvis x versus time, one line per d, the
// target dashed; written by figures/damping_figure, shared with `crowdlab reproduce gomez2024`).
#include <spdlog/spdlog.h>

#include <memory>
#include <string>
#include <vector>

#include "experiments/cli/command_table.hpp"
#include "experiments/cli/experiment_group.hpp"
#include "experiments/cli/figures/damping_figure.hpp"
#include "experiments/cli/pipeline/output_folder_lock.hpp"

namespace crowdlab::cli::cmd_experiment_damping {
namespace {

struct DampingOptions {
  std::string out_dir;
  std::vector<double> dampings{0.0, 0.006, 0.06, 0.6};
  double duration_s = 8.0;
};

}  // namespace

void add_experiment_damping_command(Command& root) {
  auto opt = std::make_shared<DampingOptions>();
  auto* cmd = experiment_group(root)->add_subcommand(
      "damping", "Seed 000 Fig. 4: a character shoved at t = 3.5 s recovering, for several dampings d");
  cmd->add_option("-o,--out", opt->out_dir, "Output folder")->required();
  cmd->add_option("--damping", opt->dampings, "Damping values d")->capture_default_str();
  cmd->add_option("--duration", opt->duration_s, "Seconds simulated")->capture_default_str();
  cmd->callback([opt] {
    const OutputFolderLock lock(opt->out_dir);  // one process per folder (output_folder_lock.hpp)
    const auto runs = run_damping_experiment(opt->dampings, CorrectorParams{}, opt->duration_s);
    for (const DampingRun& r : runs)
      spdlog::info(
          "d = {}: RMS deviation after t = 3.5 s {:.2f} mm, max {:.2f} mm, overshoot {:.2f} mm, last second "
          "{:.2f} mm",
          r.damping, 1000 * r.rms_deviation_m, 1000 * r.max_deviation_m, 1000 * r.overshoot_m,
          1000 * r.final_deviation_m);
    write_damping_figure(runs, opt->out_dir);
    spdlog::info("wrote {}/damping.csv, damping_summary.csv and damping.png|svg", opt->out_dir);
  });
}

}  // namespace crowdlab::cli::cmd_experiment_damping
