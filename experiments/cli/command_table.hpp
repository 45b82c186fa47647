#pragma once
// Every `crowdlab` command, in one explicit table (no self-registration from static objects, so the
// commands also work from a library, where unreferenced static initialisers would be dropped). Each
// add_*_command is defined in the cmd_*.cpp of the same name and adds its subcommand to `root`. Each
// cmd_*.cpp keeps its names in a namespace of its own (cmd_<file>): nearly every command has its own
// `Options` and `run`, which would clash with another command's in a unity batch (issue 31).
#include <vector>

#include "experiments/cli/command.hpp"

namespace crowdlab::cli {

namespace cmd_analyze {
void add_analyze_command(Command& root);
}
namespace cmd_bench_correct {
void add_bench_correct_command(Command& root);
}
namespace cmd_bench_crowd {
void add_bench_crowd_command(Command& root);
}
namespace cmd_bench_manifold {
void add_bench_manifold_command(Command& root);
}
namespace cmd_bench_overlap {
void add_bench_overlap_command(Command& root);
}
namespace cmd_bench_render {
void add_bench_render_command(Command& root);
}
namespace cmd_check_stimuli {
void add_check_stimuli_command(Command& root);
}
namespace cmd_correct {
void add_correct_command(Command& root);
}
namespace cmd_crowd {
void add_crowd_command(Command& root);
}
namespace cmd_demo {
void add_demo_command(Command& root);
}
namespace cmd_experiment_damping {
void add_experiment_damping_command(Command& root);
}
namespace cmd_experiment_manifold {
void add_experiment_manifold_command(Command& root);
}
namespace cmd_experiment_overlap {
void add_experiment_overlap_command(Command& root);
}
namespace cmd_export_csv {
void add_export_csv_command(Command& root);
}
namespace cmd_export_web {
void add_export_web_command(Command& root);
}
namespace cmd_help {
void add_help_command(Command& root);
}
namespace cmd_import_web {
void add_import_web_command(Command& root);
}
namespace cmd_metrics {
void add_metrics_command(Command& root);
}
namespace cmd_plan {
void add_plan_command(Command& root);
}
namespace cmd_render {
void add_render_command(Command& root);
}
namespace cmd_reproduce {
void add_reproduce_command(Command& root);
}
namespace cmd_run {
void add_run_command(Command& root);
}
namespace cmd_study {
void add_study_command(Command& root);
void add_simulate_study_command(Command& root);
void add_power_command(Command& root);
}  // namespace cmd_study
namespace cmd_validate {
void add_validate_command(Command& root);
}
namespace cmd_version {
void add_version_command(Command& root);
}

using AddCommand = void (*)(Command& root);

/// The commands in the order `crowdlab --help` lists them (the order they are added in).
const std::vector<AddCommand>& command_table();

}  // namespace crowdlab::cli
