#pragma once
// The `bench` subcommand group, shared by every `crowdlab bench <thing>` file: the first caller
// creates it, the others get it.
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
