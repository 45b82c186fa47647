#pragma once
// Subcommands register themselves: each cmd_*.cpp defines one `static const CommandRegistration`
// that adds a CLI11 subcommand. main() only builds the app and maps typed errors to exit codes.
#include <CLI/CLI.hpp>
#include <functional>
#include <vector>

namespace crowdlab::cli {

using CommandSetup = std::function<void(CLI::App& root)>;

/// Order of registration is irrelevant: subcommands are listed alphabetically by CLI11's help.
std::vector<CommandSetup>& command_registry();

struct CommandRegistration {
  explicit CommandRegistration(CommandSetup setup) { command_registry().push_back(std::move(setup)); }
};

}  // namespace crowdlab::cli
