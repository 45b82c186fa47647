#pragma once
// The `crowdlab experiment` subcommand group (paper figure reproductions): get it, or create it once.
#include <CLI/CLI.hpp>

namespace crowdlab::cli {

inline CLI::App* experiment_group(CLI::App& root) {
  try {
    return root.get_subcommand_ptr("experiment").get();
  } catch (const CLI::OptionNotFound&) {
    return root.add_subcommand("experiment", "Reproduce the papers' quantitative experiments")
        ->require_subcommand(1);
  }
}

}  // namespace crowdlab::cli
