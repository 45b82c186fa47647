// crowdlab: one binary, many subcommands. Exit codes: 0 ok, 1 runtime failure, 2 usage/invalid input.
#include <spdlog/spdlog.h>
#include <tbb/global_control.h>
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <memory>
#include <new>
#include <string>

#include "crowdlab_version.hpp"
#include "experiments/cli/command_table.hpp"
#include "experiments/cli/range_message.hpp"
#include "framework/core/error.hpp"
#include "framework/core/library_error.hpp"
#include "framework/core/printable_excerpt.hpp"
#include "framework/core/progress.hpp"

namespace {
/// The arguments after the program's name, space separated, for messages that must say what was run.
std::string command_line(int argc, char** argv) {
  std::string line;
  for (int i = 1; i < argc; ++i) line += (i > 1 ? " " : "") + std::string(argv[i]);
  return line;
}
}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"crowdlab " CROWDLAB_VERSION
               ": crowd-animation perception studies, from a YAML spec to stimuli, sessions and analysis."};
  app.require_subcommand(1);
  app.set_version_flag("--version", CROWDLAB_VERSION);
  bool quiet = false;
  std::string log_level = "info";
  app.add_flag("-q,--quiet", quiet, "Hide progress bars and info logs");
  app.add_option("--log-level", log_level, "trace|debug|info|warn|error")->capture_default_str();
  // Outputs do not depend on the thread count (docs/architecture.md, "Determinism"); the limit exists
  // for shared machines and for the test that checks exactly that (tests/determinism/).
  int threads = 0;
  std::unique_ptr<tbb::global_control> thread_limit;  // held until main returns
  app.add_option("--threads", threads, "Use at most N threads (default: every core)")
      ->check(CLI::Range(1, 4096));
  app.parse_complete_callback([&] {
    spdlog::set_level(quiet ? spdlog::level::warn : spdlog::level::from_str(log_level));
    spdlog::set_pattern("[crowdlab] %^%l%$: %v");
    crowdlab::Progress::set_enabled(!quiet);
    if (threads > 0)
      thread_limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                           static_cast<size_t>(threads));
  });
  crowdlab::cli::Command root(&app);  // holds the commands' options until parsing is done
  for (const auto add : crowdlab::cli::command_table()) add(root);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // CLI11 says only "A subcommand is required" for a misspelt command (issue 33): name it.
    if (const auto rest = app.remaining(); app.get_subcommands().empty() && !rest.empty() &&
                                           rest.front()[0] != '-' && e.get_name() == "RequiredError") {
      std::fprintf(stderr, "crowdlab: error: unknown command '%s' (crowdlab --help lists the commands)\n",
                   rest.front().c_str());
      return 2;
    }
    if (const auto readable = crowdlab::cli::readable_range_message(e.what())) {
      std::fprintf(stderr, "crowdlab: error: %s\nRun with --help for more information.\n", readable->c_str());
      return 2;
    }
    const int code = app.exit(e);  // prints help or the usage error
    return code == 0 ? 0 : 2;
  } catch (const crowdlab::InputError& e) {
    std::fprintf(stderr, "crowdlab: error: %s\n", e.what());
    return 2;
  } catch (const std::filesystem::filesystem_error& e) {
    // A folder or file the user named could not be made or read (an --out under a regular file, a
    // folder without permission): named by its path and the system's reason, as an input error (issue 33).
    std::fprintf(stderr, "crowdlab: error: %s\n", crowdlab::describe_filesystem_error(e).c_str());
    return 2;
  } catch (const std::bad_alloc&) {
    // Readers and stages that know their file turn an allocation failure into an error naming it
    // (framework/core/library_error.hpp); one that reaches here is named by the command and what it
    // was given, not by "std::bad_alloc" alone (issue 33).
    std::fprintf(stderr,
                 "crowdlab: error: out of memory in 'crowdlab %s': the inputs or options given ask for more "
                 "memory than this machine has (lower the sizes, counts or durations given)\n",
                 crowdlab::message_excerpt(command_line(argc, argv)).c_str());
    return 1;
  } catch (const std::exception& e) {
    // A library's bare message (a JSON type error, "stod", Boost.Math) that no reader turned into an
    // InputError naming its file: named by the command line that was run, exit 2 (issue 33).
    try {
      crowdlab::rethrow_library_error_as_input("'crowdlab " +
                                               crowdlab::message_excerpt(command_line(argc, argv)) + "'");
    } catch (const crowdlab::InputError& named) {
      std::fprintf(stderr, "crowdlab: error: %s\n", named.what());
      return 2;
    } catch (...) {
    }
    std::fprintf(stderr, "crowdlab: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
