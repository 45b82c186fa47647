// The table of command_table.hpp. The order is the one `crowdlab --help` and docs/cli.md list the
// commands in; `bench` and `experiment` are created by their first member.
#include "experiments/cli/command_table.hpp"

namespace crowdlab::cli {

const std::vector<AddCommand>& command_table() {
  static const std::vector<AddCommand> table = {
      add_analyze_command,
      add_bench_correct_command,
      add_bench_crowd_command,
      add_bench_manifold_command,
      add_bench_overlap_command,
      add_bench_render_command,
      add_check_stimuli_command,
      add_correct_command,
      add_crowd_command,
      add_demo_command,
      add_experiment_damping_command,
      add_experiment_manifold_command,
      add_experiment_overlap_command,
      add_export_csv_command,
      add_export_web_command,
      add_help_command,
      add_import_web_command,
      add_metrics_command,
      add_plan_command,
      add_render_command,
      add_reproduce_command,
      add_run_command,
      add_study_command,
      add_simulate_study_command,
      add_power_command,
      add_validate_command,
      add_version_command,
  };
  return table;
}

}  // namespace crowdlab::cli
