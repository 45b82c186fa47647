#pragma once
// The shared `crowdlab bench` subcommand group: every benchmark command adds itself under it.
#include <CLI/CLI.hpp>

namespace crowdlab::cli {

/// Gets the `bench` subcommand of `root`, creating it on first use.
inline CLI::App* bench_group(CLI::App& root) {
  try {
    return root.get_subcommand_ptr("bench").get();
  } catch (const CLI::OptionNotFound&) {
    return root.add_subcommand("bench", "Benchmarks (median timings)")->require_subcommand(1);
  }
}

}  // namespace crowdlab::cli
