#include "framework/spec/parse_factor.hpp"

#include <cmath>

#include "framework/core/viewpoint_catalogue.hpp"
#include "framework/spec/did_you_mean.hpp"

namespace crowdlab {
namespace {

enum class LevelKind { kNumber, kWhole, kChoice };

struct FactorRule {
  std::string name;
  LevelKind kind;
  Range range{0.0, 0.0};
  std::vector<std::string> choices;
  std::string units;  ///< for messages
};

// The scenario kinds, plus seed 001 §4.2.1's names for its flows (A, B; framework/spec/type_condition.cpp).
std::vector<std::string> scenario_level_names() {
  std::vector<std::string> names = kind_names<ScenarioKind>();
  names.insert(names.end(), {"A", "B"});
  return names;
}

const std::vector<FactorRule>& factor_rules() {
  static const std::vector<FactorRule> rules = {
      {"density", LevelKind::kNumber, Range{0.0, 10.0, true, false}, {}, "characters per m^2"},
      {"characters", LevelKind::kWhole, Range{1.0, 10000.0}, {}, "characters"},
      {"viewpoint", LevelKind::kChoice, {}, viewpoint_names(), ""},
      {"method", LevelKind::kChoice, {}, kind_names<CrowdMethod>(), ""},
      {"shoulder", LevelKind::kWhole, Range{0.0, 2.0}, {}, "characters with shoulder motions"},
      {"distance", LevelKind::kNumber, Range{0.0, 10.0, true, false}, {}, "metres"},
      {"trigger", LevelKind::kNumber, Range{0.0, 100.0}, {}, "percent"},
      {"scenario", LevelKind::kChoice, {}, scenario_level_names(), ""},
      {"side", LevelKind::kChoice, {}, {"left", "right"}, ""},
  };
  return rules;
}

const FactorRule* find_rule(const std::string& name) {
  for (const FactorRule& r : factor_rules())
    if (r.name == name) return &r;
  return nullptr;
}

bool id_safe(const std::string& text) {
  if (text.empty()) return false;
  for (char c : text) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' ||
                    c == '+' || c == '-';
    if (!ok) return false;
  }
  return true;
}

std::optional<FactorLevel> parse_level(SpecDiagnostics& diag, const FactorRule& rule, const YAML::Node& node,
                                       const std::string& path) {
  if (!node.IsScalar()) {
    diag.error(node, path, "a level must be a single value, got " + describe_node(node));
    return std::nullopt;
  }
  FactorLevel level;
  level.text = node.Scalar();
  if (rule.kind == LevelKind::kChoice) {
    for (const std::string& c : rule.choices)
      if (c == level.text) return level;
    diag.error(
        node, path,
        "invalid " + rule.name + " level '" + level.text + "'" + suggestion_suffix(level.text, rule.choices));
    return std::nullopt;
  }
  if (rule.name == "trigger" && !level.text.empty() && level.text.back() == '%') level.text.pop_back();
  YAML::Node number_node(level.text);
  double v = 0.0;
  if (!YAML::convert<double>::decode(number_node, v) || !std::isfinite(v)) {
    diag.error(node, path,
               rule.name + " levels are numbers (" + rule.units + "), got " + describe_node(node));
    return std::nullopt;
  }
  if (!rule.range.contains(v)) {
    diag.error(node, path,
               rule.name + " level must be in " + rule.range.text() + " (" + rule.units + "), got " +
                   format_number(v));
    return std::nullopt;
  }
  if (rule.kind == LevelKind::kWhole && v != std::floor(v)) {
    diag.error(node, path, rule.name + " levels are whole numbers, got " + describe_node(node));
    return std::nullopt;
  }
  if (!id_safe(level.text)) {
    diag.error(node, path, "level text '" + level.text + "' may only contain letters, digits, '.', '+', '-'");
    return std::nullopt;
  }
  level.number = v;
  return level;
}

}  // namespace

const std::vector<std::string>& known_factor_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const FactorRule& r : factor_rules()) n.push_back(r.name);
    return n;
  }();
  return names;
}

std::optional<Factor> parse_factor(SpecDiagnostics& diag, const std::string& name, const YAML::Node& node,
                                   const std::string& path) {
  const FactorRule* rule = find_rule(name);
  if (!rule) {
    diag.error(node, path, "unknown factor '" + name + "'" + suggestion_suffix(name, known_factor_names()));
    return std::nullopt;
  }
  YAML::Node list = node;
  std::string list_path = path;
  if (node.IsMap()) {
    YamlSection s(diag, node, path);
    s.allow_keys({"levels"});
    if (!s.require("levels")) return std::nullopt;
    list = s.get("levels");
    list_path = path + ".levels";
  }
  if (!list.IsSequence()) {
    diag.error(list, list_path, "expected a list of levels, got " + describe_node(list));
    return std::nullopt;
  }
  if (list.size() == 0) {
    diag.error(list, list_path, "a factor needs at least one level");
    return std::nullopt;
  }
  if (list.size() > kMaxFactorLevels) {
    diag.error(list, list_path,
               "lists " + std::to_string(list.size()) + " levels, more than the limit of " +
                   std::to_string(kMaxFactorLevels) +
                   " (the condition limit); split the study into several specs");
    return std::nullopt;
  }
  Factor factor;
  factor.name = name;
  bool ok = true;
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string level_path = list_path + "[" + std::to_string(i) + "]";
    auto level = parse_level(diag, *rule, list[i], level_path);
    if (!level) {
      ok = false;
      continue;
    }
    for (const FactorLevel& earlier : factor.levels) {
      const bool same = earlier.text == level->text ||
                        (earlier.number && level->number && *earlier.number == *level->number);
      if (same) {
        diag.error(list[i], level_path,
                   "duplicate level '" + level->text + "' (same as '" + earlier.text + "')");
        ok = false;
        break;  // one message per repeated level, not one per earlier copy
      }
    }
    factor.levels.push_back(*level);
  }
  if (!ok) return std::nullopt;
  return factor;
}

}  // namespace crowdlab
