// The table of command_table.hpp. The order is the one `crowdlab --help` and docs/cli.md list the
// commands in; `bench` and `experiment` are created by their first member.
#include "experiments/cli/command_table.hpp"

namespace crowdlab::cli {

const std::vector<AddCommand>& command_table() {
  static const std::vector<AddCommand> table = {
      cmd_analyze::add_analyze_command,
      cmd_bench_correct::add_bench_correct_command,
      cmd_bench_crowd::add_bench_crowd_command,
      cmd_bench_manifold::add_bench_manifold_command,
      cmd_bench_overlap::add_bench_overlap_command,
      cmd_bench_render::add_bench_render_command,
      cmd_check_stimuli::add_check_stimuli_command,
      cmd_correct::add_correct_command,
      cmd_crowd::add_crowd_command,
      cmd_demo::add_demo_command,
      cmd_experiment_damping::add_experiment_damping_command,
      cmd_experiment_manifold::add_experiment_manifold_command,
      cmd_experiment_overlap::add_experiment_overlap_command,
      cmd_export_csv::add_export_csv_command,
      cmd_export_web::add_export_web_command,
      cmd_help::add_help_command,
      cmd_import_web::add_import_web_command,
      cmd_metrics::add_metrics_command,
      cmd_plan::add_plan_command,
      cmd_render::add_render_command,
      cmd_reproduce::add_reproduce_command,
      cmd_run::add_run_command,
      cmd_study::add_study_command,
      cmd_study::add_simulate_study_command,
      cmd_study::add_power_command,
      cmd_validate::add_validate_command,
      cmd_version::add_version_command,
  };
  return table;
}

}  // namespace crowdlab::cli
