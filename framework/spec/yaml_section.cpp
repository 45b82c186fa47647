#include "framework/spec/yaml_section.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <set>

#include "framework/spec/did_you_mean.hpp"

namespace crowdlab {

void SpecDiagnostics::error(const YAML::Mark& at, const std::string& key_path, const std::string& message) {
  std::string m = source_name;
  if (at.line >= 0) m += ":" + std::to_string(at.line + 1) + ":" + std::to_string(at.column + 1);
  m += ": ";
  if (!key_path.empty()) m += key_path + ": ";
  messages.push_back(m + message);
  positions.emplace_back(at.line, at.column);
}

std::vector<std::string> SpecDiagnostics::sorted_messages() const {
  std::vector<size_t> order(messages.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return positions[a] < positions[b]; });
  std::vector<std::string> out;
  for (size_t i : order) out.push_back(messages[i]);
  return out;
}

void SpecDiagnostics::error(const YAML::Node& at, const std::string& key_path, const std::string& message) {
  error(at.IsDefined() ? at.Mark() : YAML::Mark::null_mark(), key_path, message);
}

bool Range::contains(double v) const {
  const bool above = lo_open ? v > lo : v >= lo;
  const bool below = hi_open ? v < hi : v <= hi;
  return above && below;
}

std::string Range::text() const {
  if (hi >= 1e299) return std::string(lo_open ? "> " : ">= ") + format_number(lo);
  return std::string(lo_open ? "(" : "[") + format_number(lo) + ", " + format_number(hi) +
         (hi_open ? ")" : "]");
}

std::string format_number(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

std::string describe_node(const YAML::Node& node) {
  if (!node.IsDefined() || node.IsNull()) return "nothing";
  if (node.IsMap()) return "a map";
  if (node.IsSequence()) return "a list";
  return "'" + node.Scalar() + "'";
}

std::optional<double> parse_number(SpecDiagnostics& diag, const YAML::Node& node, const std::string& path,
                                   const Range& range) {
  if (!node.IsScalar()) {
    diag.error(node, path, "expected a number, got " + describe_node(node));
    return std::nullopt;
  }
  double v = 0.0;
  if (!YAML::convert<double>::decode(node, v)) {
    diag.error(node, path, "expected a number, got " + describe_node(node));
    return std::nullopt;
  }
  if (!std::isfinite(v)) {
    diag.error(node, path, "must be a finite number, got " + describe_node(node));
    return std::nullopt;
  }
  if (!range.contains(v)) {
    diag.error(
        node, path,
        "must be " + (range.hi >= 1e299 ? range.text() : "in " + range.text()) + ", got " + format_number(v));
    return std::nullopt;
  }
  return v;
}

std::optional<int> parse_integer(SpecDiagnostics& diag, const YAML::Node& node, const std::string& path,
                                 int lo, int hi) {
  if (!node.IsScalar()) {
    diag.error(node, path, "expected a whole number, got " + describe_node(node));
    return std::nullopt;
  }
  long long v = 0;
  if (!YAML::convert<long long>::decode(node, v)) {
    diag.error(node, path, "expected a whole number, got " + describe_node(node));
    return std::nullopt;
  }
  if (v < lo || v > hi) {
    diag.error(
        node, path,
        "must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " + std::to_string(v));
    return std::nullopt;
  }
  return static_cast<int>(v);
}

std::optional<std::string> parse_string(SpecDiagnostics& diag, const YAML::Node& node,
                                        const std::string& path) {
  if (!node.IsScalar()) {
    diag.error(node, path, "expected text, got " + describe_node(node));
    return std::nullopt;
  }
  return node.Scalar();
}

std::optional<std::string> resolve_existing_path(SpecDiagnostics& diag, const YAML::Node& node,
                                                 const std::string& path, const std::string& relative,
                                                 bool directory) {
  namespace fs = std::filesystem;
  if (relative.empty()) {
    diag.error(node, path, "empty path");
    return std::nullopt;
  }
  fs::path p(relative);
  if (p.is_relative()) p = fs::path(diag.base_dir.empty() ? "." : diag.base_dir) / p;
  p = p.lexically_normal();
  std::error_code ec;
  const bool ok = directory ? fs::is_directory(p, ec) : fs::is_regular_file(p, ec);
  if (!ok) {
    diag.error(node, path,
               std::string(directory ? "folder" : "file") + " not found: '" + relative + "' (looked for " +
                   p.string() + ")");
    return std::nullopt;
  }
  return p.string();
}

YamlSection::YamlSection(SpecDiagnostics& diag, YAML::Node node, std::string path)
    : diag_(&diag), node_(std::move(node)), path_(std::move(path)) {
  if (!node_.IsDefined() || node_.IsNull()) return;  // absent: all defaults
  if (!node_.IsMap()) {
    diag.error(node_, path_, "expected a map of keys, got " + describe_node(node_));
    return;
  }
  valid_ = true;
}

bool YamlSection::has(const std::string& key) const {
  return valid_ && node_[key].IsDefined();
}

YAML::Node YamlSection::get(const std::string& key) const {
  if (!valid_) return YAML::Node(YAML::NodeType::Undefined);
  const YAML::Node& n = node_;
  return n[key];
}

void YamlSection::allow_keys(const std::vector<std::string>& allowed) {
  if (!valid_) return;
  std::set<std::string> seen;
  for (auto it = node_.begin(); it != node_.end(); ++it) {
    const YAML::Node key = it->first;
    if (!key.IsScalar()) {
      diag_->error(key, path_, "keys must be plain names, got " + describe_node(key));
      continue;
    }
    const std::string name = key.Scalar();
    if (!seen.insert(name).second) diag_->error(key, child_path(name), "duplicate key");
    bool known = false;
    for (const std::string& a : allowed) known = known || a == name;
    if (!known) diag_->error(key, child_path(name), "unknown key" + suggestion_suffix(name, allowed));
  }
}

bool YamlSection::require(const std::string& key) {
  if (has(key)) return true;
  diag_->error(valid_ ? node_ : YAML::Node(), child_path(key), "required key is missing");
  return false;
}

void YamlSection::number(const std::string& key, double& out, const Range& range) {
  if (!has(key)) return;
  if (auto v = parse_number(*diag_, get(key), child_path(key), range)) out = *v;
}

void YamlSection::integer(const std::string& key, int& out, int lo, int hi) {
  if (!has(key)) return;
  if (auto v = parse_integer(*diag_, get(key), child_path(key), lo, hi)) out = *v;
}

void YamlSection::seed(const std::string& key, std::uint64_t& out) {
  if (!has(key)) return;
  const YAML::Node n = get(key);
  std::uint64_t v = 0;
  if (!n.IsScalar() || n.Scalar().empty() || n.Scalar()[0] == '-' ||
      !YAML::convert<std::uint64_t>::decode(n, v)) {
    diag_->error(n, child_path(key), "expected a whole number in [0, 2^64), got " + describe_node(n));
    return;
  }
  out = v;
}

void YamlSection::boolean(const std::string& key, bool& out) {
  if (!has(key)) return;
  const YAML::Node n = get(key);
  bool v = false;
  if (!n.IsScalar() || !YAML::convert<bool>::decode(n, v)) {
    diag_->error(n, child_path(key), "expected true or false, got " + describe_node(n));
    return;
  }
  out = v;
}

void YamlSection::string(const std::string& key, std::string& out) {
  if (!has(key)) return;
  if (auto v = parse_string(*diag_, get(key), child_path(key))) out = *v;
}

void YamlSection::choice(const std::string& key, std::string& out, const std::vector<std::string>& choices) {
  if (!has(key)) return;
  const YAML::Node n = get(key);
  auto v = parse_string(*diag_, n, child_path(key));
  if (!v) return;
  for (const std::string& c : choices)
    if (c == *v) {
      out = *v;
      return;
    }
  diag_->error(n, child_path(key), "invalid value '" + *v + "'" + suggestion_suffix(*v, choices));
}

void YamlSection::string_list(const std::string& key, std::vector<std::string>& out) {
  if (!has(key)) return;
  const YAML::Node n = get(key);
  if (!n.IsSequence()) {
    diag_->error(n, child_path(key), "expected a list of text items, got " + describe_node(n));
    return;
  }
  std::vector<std::string> values;
  for (size_t i = 0; i < n.size(); ++i)
    if (auto v = parse_string(*diag_, n[i], child_path(key) + "[" + std::to_string(i) + "]"))
      values.push_back(*v);
  if (values.size() == n.size()) out = std::move(values);
}

void YamlSection::number_list(const std::string& key, std::vector<double>& out, const Range& range) {
  if (!has(key)) return;
  const YAML::Node n = get(key);
  if (!n.IsSequence()) {
    diag_->error(n, child_path(key), "expected a list of numbers, got " + describe_node(n));
    return;
  }
  std::vector<double> values;
  for (size_t i = 0; i < n.size(); ++i)
    if (auto v = parse_number(*diag_, n[i], child_path(key) + "[" + std::to_string(i) + "]", range))
      values.push_back(*v);
  if (values.size() == n.size()) out = std::move(values);
}

void YamlSection::existing_path(const std::string& key, std::string& out, bool directory) {
  if (!has(key)) return;
  const YAML::Node n = get(key);
  auto v = parse_string(*diag_, n, child_path(key));
  if (!v) return;
  if (auto p = resolve_existing_path(*diag_, n, child_path(key), *v, directory)) out = *p;
}

YamlSection YamlSection::section(const std::string& key) const {
  return YamlSection(*diag_, get(key), child_path(key));
}

}  // namespace crowdlab
