#pragma once
// Every `crowdlab` command, in one explicit table (no self-registration from static objects, so the
// commands also work from a library, where unreferenced static initialisers would be dropped). Each
// add_*_command is defined in the cmd_*.cpp of the same name and adds its subcommand to `root`.
#include <vector>

#include "experiments/cli/command.hpp"

namespace crowdlab::cli {

void add_analyze_command(Command& root);
void add_bench_correct_command(Command& root);
void add_bench_crowd_command(Command& root);
void add_bench_manifold_command(Command& root);
void add_bench_overlap_command(Command& root);
void add_bench_render_command(Command& root);
void add_check_stimuli_command(Command& root);
void add_correct_command(Command& root);
void add_crowd_command(Command& root);
void add_demo_command(Command& root);
void add_experiment_damping_command(Command& root);
void add_experiment_manifold_command(Command& root);
void add_experiment_overlap_command(Command& root);
void add_export_csv_command(Command& root);
void add_export_web_command(Command& root);
void add_help_command(Command& root);
void add_import_web_command(Command& root);
void add_metrics_command(Command& root);
void add_plan_command(Command& root);
void add_render_command(Command& root);
void add_reproduce_command(Command& root);
void add_run_command(Command& root);
void add_study_command(Command& root);
void add_simulate_study_command(Command& root);
void add_power_command(Command& root);
void add_validate_command(Command& root);
void add_version_command(Command& root);

using AddCommand = void (*)(Command& root);

/// The commands in the order `crowdlab --help` lists them (the order they are added in).
const std::vector<AddCommand>& command_table();

}  // namespace crowdlab::cli
