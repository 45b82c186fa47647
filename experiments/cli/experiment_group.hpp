#pragma once
// The `crowdlab experiment` subcommand group (paper figure reproductions): get it, or create it once.
#include "experiments/cli/command.hpp"

namespace crowdlab::cli {

inline Command* experiment_group(Command& root) {
  if (Command* group = root.find_subcommand("experiment")) return group;
  return root.add_subcommand("experiment", "Reproduce the papers' quantitative experiments")
      ->require_subcommand(1);
}

}  // namespace crowdlab::cli
