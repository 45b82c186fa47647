#pragma once
// Typed, error-collecting reading of one YAML mapping (internal to the spec loader).
//
// A YamlSection is a mapping node plus its dotted key path ("protocol.scale"). Each accessor reads one
// optional key into a caller-owned field (which already holds the default), checks its type and range,
// and on any problem records "file:line:column: key.path: message" in the shared SpecDiagnostics and
// leaves the field unchanged, so loading continues and every problem in a spec is reported at once.
// Line and column are 1-based (yaml-cpp's Mark is 0-based).
#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "framework/spec/condition_kinds.hpp"

namespace crowdlab {

/// The list of problems found so far, plus what messages need (the file name and spec folder).
struct SpecDiagnostics {
  std::string source_name;
  std::string base_dir;
  std::vector<std::string> messages;
  std::vector<std::pair<int, int>> positions;  ///< (line, column) of each message, 0-based; -1 unknown

  void error(const YAML::Mark& at, const std::string& key_path, const std::string& message);
  void error(const YAML::Node& at, const std::string& key_path, const std::string& message);
  /// The messages in file order (by line, then column; unknown positions first), for reporting.
  std::vector<std::string> sorted_messages() const;
};

/// A closed or half-open numeric interval for range checks; printed as "(0, 1]" etc.
struct Range {
  double lo;
  double hi;
  bool lo_open = false;
  bool hi_open = false;
  bool contains(double v) const;
  std::string text() const;
  static Range positive(double hi = 1e300) { return {0.0, hi, true, false}; }
  static Range non_negative(double hi = 1e300) { return {0.0, hi, false, false}; }
};

/// Formats a double compactly for messages ("2.5", "1e-06").
std::string format_number(double v);

/// Human name of a node's type for "expected X, got Y" messages: "a map", "a list", "a number"...
std::string describe_node(const YAML::Node& node);

/// Scalar parsers that report into `diag` and return nullopt on failure.
std::optional<double> parse_number(SpecDiagnostics& diag, const YAML::Node& node, const std::string& path,
                                   const Range& range);
std::optional<int> parse_integer(SpecDiagnostics& diag, const YAML::Node& node, const std::string& path,
                                 int lo, int hi);
std::optional<std::string> parse_string(SpecDiagnostics& diag, const YAML::Node& node,
                                        const std::string& path);

class YamlSection {
 public:
  /// `node` must be a map (or absent/null, meaning "all defaults"); otherwise an error is recorded.
  YamlSection(SpecDiagnostics& diag, YAML::Node node, std::string path);

  bool present() const { return valid_; }
  bool has(const std::string& key) const;
  const YAML::Node& node() const { return node_; }
  const std::string& path() const { return path_; }
  std::string child_path(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
  YAML::Node get(const std::string& key) const;

  /// Records every key not in `allowed` (with a did-you-mean suggestion) and every duplicated key.
  void allow_keys(const std::vector<std::string>& allowed);
  /// Records an error when `key` is absent.
  bool require(const std::string& key);

  void number(const std::string& key, double& out, const Range& range);
  void integer(const std::string& key, int& out, int lo, int hi);
  void seed(const std::string& key, std::uint64_t& out);
  void boolean(const std::string& key, bool& out);
  void string(const std::string& key, std::string& out);
  /// A string that must be one of `choices` (did-you-mean on mismatch).
  void choice(const std::string& key, std::string& out, const std::vector<std::string>& choices);
  /// choice() into one of the enums of framework/spec/condition_kinds.hpp, by its spellings.
  template <class E>
  void choice(const std::string& key, E& out) {
    std::string text(kind_name(out));
    choice(key, text, kind_names<E>());
    if (const auto value = parse_kind<E>(text)) out = *value;
  }
  void string_list(const std::string& key, std::vector<std::string>& out);
  void number_list(const std::string& key, std::vector<double>& out, const Range& range);
  /// A path relative to the spec folder; `out` receives the resolved path. `directory` selects
  /// whether a folder or a regular file must exist there.
  void existing_path(const std::string& key, std::string& out, bool directory);
  YamlSection section(const std::string& key) const;
  SpecDiagnostics& diagnostics() const { return *diag_; }

 private:
  SpecDiagnostics* diag_;
  YAML::Node node_;
  std::string path_;
  bool valid_ = false;
};

/// Resolves `relative` against the spec folder and checks it exists (reporting at `node`).
std::optional<std::string> resolve_existing_path(SpecDiagnostics& diag, const YAML::Node& node,
                                                 const std::string& path, const std::string& relative,
                                                 bool directory);

}  // namespace crowdlab
