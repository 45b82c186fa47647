#pragma once
// The `crowdlab bench` subcommand group, shared by every benchmark: get it, or create it once.
#include "experiments/cli/command.hpp"

namespace crowdlab::cli {

inline Command* bench_group(Command& root) {
  if (Command* group = root.find_subcommand("bench")) return group;
  return root.add_subcommand("bench", "Benchmarks (median timings)")->require_subcommand(1);
}

}  // namespace crowdlab::cli
