#pragma once
// The `crowdlab bench` subcommand group, shared by every benchmark: get it, or create it once.
#include <CLI/CLI.hpp>

namespace crowdlab::cli {

inline CLI::App* bench_group(CLI::App& root) {
  try {
    return root.get_subcommand_ptr("bench").get();
  } catch (const CLI::OptionNotFound&) {
    return root.add_subcommand("bench", "Benchmarks (median timings)")->require_subcommand(1);
  }
}

}  // namespace crowdlab::cli
