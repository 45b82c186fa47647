// The one place the command declarations meet CLI11 (command.hpp says why). Every call forwards to the
// CLI11 call of the same name with the same argument types, so the help texts stay byte-identical.
#include "experiments/cli/command.hpp"

#include <CLI/CLI.hpp>

namespace crowdlab::cli {

namespace check {
Check range(int min, int max) {
  return {Check::Kind::kIntRange, double(min), double(max), {}};
}
Check range(double min, double max) {
  return {Check::Kind::kDoubleRange, min, max, {}};
}
Check existing_file() {
  return {Check::Kind::kExistingFile, 0.0, 0.0, {}};
}
Check existing_directory() {
  return {Check::Kind::kExistingDirectory, 0.0, 0.0, {}};
}
Check positive_number() {
  return {Check::Kind::kPositiveNumber, 0.0, 0.0, {}};
}
Check is_member(std::vector<std::string> members) {
  return {Check::Kind::kIsMember, 0.0, 0.0, std::move(members)};
}
}  // namespace check

Option* Option::required() {
  option_->required();
  return this;
}

Option* Option::capture_default_str() {
  option_->capture_default_str();
  return this;
}

Option* Option::check(const Check& c) {
  switch (c.kind) {
    case Check::Kind::kIntRange:
      option_->check(CLI::Range(static_cast<int>(c.min), static_cast<int>(c.max)));
      break;
    case Check::Kind::kDoubleRange:
      option_->check(CLI::Range(c.min, c.max));
      break;
    case Check::Kind::kExistingFile:
      option_->check(CLI::ExistingFile);
      break;
    case Check::Kind::kExistingDirectory:
      option_->check(CLI::ExistingDirectory);
      break;
    case Check::Kind::kPositiveNumber:
      option_->check(CLI::PositiveNumber);
      break;
    case Check::Kind::kIsMember:
      option_->check(CLI::IsMember(c.members));
      break;
  }
  return this;
}

Option* Option::excludes(Option* other) {
  option_->excludes(other->option_);
  return this;
}

Option* Option::each(std::function<void(const std::string&)> fn) {
  option_->each(std::move(fn));
  return this;
}

Command* Command::add_subcommand(const std::string& name, const std::string& description) {
  return &subcommands_.emplace_back(app_->add_subcommand(name, description));
}

Command* Command::find_subcommand(const std::string& name) {
  for (Command& sub : subcommands_)
    if (sub.app_->get_name() == name) return &sub;
  return nullptr;
}

Command* Command::require_subcommand(int count) {
  app_->require_subcommand(count);
  return this;
}

void Command::callback(std::function<void()> fn) {
  app_->callback(std::move(fn));
}

Option* Command::keep(CLI::Option* option) {
  return &options_.emplace_back(option);
}

Option* Command::add_option(const std::string& name, std::string& value, const std::string& description) {
  return keep(app_->add_option(name, value, description));
}
Option* Command::add_option(const std::string& name, int& value, const std::string& description) {
  return keep(app_->add_option(name, value, description));
}
Option* Command::add_option(const std::string& name, double& value, const std::string& description) {
  return keep(app_->add_option(name, value, description));
}
Option* Command::add_option(const std::string& name, bool& value, const std::string& description) {
  return keep(app_->add_option(name, value, description));
}
Option* Command::add_option(const std::string& name, std::uint64_t& value, const std::string& description) {
  return keep(app_->add_option(name, value, description));
}
Option* Command::add_option(const std::string& name, std::vector<std::string>& value,
                            const std::string& description) {
  return keep(app_->add_option(name, value, description));
}
Option* Command::add_option(const std::string& name, std::vector<double>& value,
                            const std::string& description) {
  return keep(app_->add_option(name, value, description));
}
Option* Command::add_option(const std::string& name, std::vector<int>& value,
                            const std::string& description) {
  return keep(app_->add_option(name, value, description));
}
Option* Command::add_flag(const std::string& name, bool& value, const std::string& description) {
  return keep(app_->add_flag(name, value, description));
}
Option* Command::add_flag_callback(const std::string& name, std::function<void()> fn,
                                   const std::string& description) {
  return keep(app_->add_flag_callback(name, std::move(fn), description));
}

}  // namespace crowdlab::cli
