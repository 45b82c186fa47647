#pragma once
// The command-line declarations every `cmd_*.cpp` makes (subcommands, options, flags, checks), without
// CLI11: a thin facade whose one implementation (command.cpp) forwards each call to CLI11 unchanged, so
// help texts, parsing and errors are CLI11's. Why: CLI11 is header-only and its templates cost about 20 s
// of -O3 compile per translation unit that instantiates them (issue 31); behind this facade only
// main.cpp, command.cpp and cmd_help.cpp include it.
//
// The calls mirror CLI11's (`cmd->add_option("--out", o->out, "help")->required()->check(...)`); the
// validators are the ones under `check::` below. Option and Command objects live as long as the root
// Command they were added to (main() holds it until parsing is done).
#include <cstdint>
#include <functional>
#include <list>
#include <memory>
#include <string>
#include <vector>

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace crowdlab::cli {

/// A validator of an option's value (CLI11's Range, ExistingFile, ExistingDirectory, PositiveNumber,
/// IsMember). The kind and bounds are kept as data; command.cpp builds the CLI11 validator, so the help
/// text names the same type ("INT in [1 - 32]", "FLOAT in [0 - 1]") as a direct CLI11 call would.
struct Check {
  enum class Kind { kIntRange, kDoubleRange, kExistingFile, kExistingDirectory, kPositiveNumber, kIsMember };
  Kind kind = Kind::kExistingFile;
  double min = 0.0, max = 0.0;
  std::vector<std::string> members;
};

namespace check {
Check range(int min, int max);                      // CLI::Range(int, int)
Check range(double min, double max);                // CLI::Range(double, double)
Check existing_file();                              // CLI::ExistingFile
Check existing_directory();                         // CLI::ExistingDirectory
Check positive_number();                            // CLI::PositiveNumber
Check is_member(std::vector<std::string> members);  // CLI::IsMember
}  // namespace check

/// One option or flag of a command; the modifiers return the option, as CLI11's do.
class Option {
 public:
  explicit Option(CLI::Option* option) : option_(option) {}
  Option* required();
  Option* capture_default_str();
  Option* check(const Check& check);
  Option* excludes(Option* other);
  /// Called with each value given on the command line (after parsing, before the command's callback).
  Option* each(std::function<void(const std::string&)> fn);

 private:
  CLI::Option* option_;
};

/// A command or subcommand. add_option/add_flag bind a variable that must outlive the parse (the
/// commands keep their options in a shared_ptr captured by their callback).
class Command {
 public:
  explicit Command(CLI::App* app) : app_(app) {}
  Command(const Command&) = delete;
  Command& operator=(const Command&) = delete;

  Command* add_subcommand(const std::string& name, const std::string& description);
  /// The subcommand `name` added before, or nullptr (for groups such as `bench` that several files extend).
  Command* find_subcommand(const std::string& name);
  Command* require_subcommand(int count);
  void callback(std::function<void()> fn);

  Option* add_option(const std::string& name, std::string& value, const std::string& description);
  Option* add_option(const std::string& name, int& value, const std::string& description);
  Option* add_option(const std::string& name, double& value, const std::string& description);
  Option* add_option(const std::string& name, bool& value, const std::string& description);
  Option* add_option(const std::string& name, std::uint64_t& value, const std::string& description);
  Option* add_option(const std::string& name, std::vector<std::string>& value,
                     const std::string& description);
  Option* add_option(const std::string& name, std::vector<double>& value, const std::string& description);
  Option* add_option(const std::string& name, std::vector<int>& value, const std::string& description);
  Option* add_flag(const std::string& name, bool& value, const std::string& description);
  Option* add_flag_callback(const std::string& name, std::function<void()> fn,
                            const std::string& description);

  /// The CLI11 app behind this command, for the few files that include CLI11 (main.cpp, cmd_help.cpp).
  CLI::App* app() const { return app_; }

 private:
  Option* keep(CLI::Option* option);

  CLI::App* app_;
  std::list<Command> subcommands_;  // list: pointers handed out stay valid as more are added
  std::list<Option> options_;
};

}  // namespace crowdlab::cli
