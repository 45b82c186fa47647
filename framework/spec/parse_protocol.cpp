#include "framework/spec/parse_protocol.hpp"

#include <set>

#include "framework/spec/did_you_mean.hpp"
#include "framework/spec/parse_factor.hpp"

namespace crowdlab {
namespace {

constexpr int kMinScalePoints = 2;
constexpr int kMaxScalePoints = 11;

bool is_identifier(const std::string& s) {
  if (s.empty()) return false;
  for (char c : s)
    if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_'))
      return false;
  return true;
}

void check_label_count(YamlSection& s, const std::string& key, size_t labels, int points) {
  if (labels == 0 || points == 0) return;
  if (labels != 2 && labels != static_cast<size_t>(points))
    s.diagnostics().error(s.get(key), s.child_path(key),
                          "give 2 anchor labels (lowest, highest) or one per point (" +
                              std::to_string(points) + "), got " + std::to_string(labels));
}

/// An absolute http(s) URL with a host and no whitespace or quotes (it ends up in a web page's link).
bool is_web_url(const std::string& url) {
  const std::string http = "http://", https = "https://";
  size_t host = 0;
  if (url.compare(0, https.size(), https) == 0)
    host = https.size();
  else if (url.compare(0, http.size(), http) == 0)
    host = http.size();
  else
    return false;
  if (url.size() <= host || url[host] == '/') return false;
  for (char c : url)
    if (c <= ' ' || c == '"' || c == '\'' || c == '<' || c == '>' || c == '\\' || c == 127) return false;
  return true;
}

std::vector<std::string> factor_names(const ExperimentSpec& spec) {
  std::vector<std::string> names;
  for (const Factor& f : spec.factors) names.push_back(f.name);
  return names;
}

void parse_questions(YamlSection& protocol, ProtocolSpec& p) {
  SpecDiagnostics& diag = protocol.diagnostics();
  if (!protocol.require("questions")) return;
  const YAML::Node list = protocol.get("questions");
  const std::string path = protocol.child_path("questions");
  if (!list.IsSequence() || list.size() == 0) {
    diag.error(list, path, "expected a non-empty list of questions, got " + describe_node(list));
    return;
  }
  std::set<std::string> ids;
  for (size_t i = 0; i < list.size(); ++i) {
    YamlSection q(diag, list[i], path + "[" + std::to_string(i) + "]");
    if (!q.present()) {
      if (list[i].IsNull()) diag.error(list[i], q.path(), "expected a question {id, text, ...}, got nothing");
      continue;
    }
    q.allow_keys({"id", "text", "reverse", "kind", "points", "labels"});
    QuestionSpec question;
    if (q.require("id")) {
      q.string("id", question.id);
      if (!is_identifier(question.id))
        diag.error(q.get("id"), q.child_path("id"), "question ids may only contain letters, digits and '_'");
      else if (!ids.insert(question.id).second)
        diag.error(q.get("id"), q.child_path("id"), "duplicate question id '" + question.id + "'");
    }
    if (q.require("text")) q.string("text", question.text);
    q.choice("kind", question.kind, {"scale", "yesno"});
    q.boolean("reverse", question.reverse);
    q.integer("points", question.points, 0, kMaxScalePoints);
    if (question.points == 1)
      diag.error(q.get("points"), q.child_path("points"), "a scale needs at least 2 points");
    q.string_list("labels", question.labels);
    if (question.kind == "yesno") {
      if (question.reverse)
        diag.error(q.get("reverse"), q.child_path("reverse"), "a yes/no question cannot be reverse-keyed");
      if (q.has("points"))
        diag.error(q.get("points"), q.child_path("points"), "a yes/no question has no scale points");
      if (!question.labels.empty() && question.labels.size() != 2)
        diag.error(q.get("labels"), q.child_path("labels"), "a yes/no question takes 2 labels (yes, no)");
    } else {
      check_label_count(q, "labels", question.labels.size(),
                        question.points ? question.points : p.scale_points);
    }
    p.questions.push_back(question);
  }
}

void parse_composites(YamlSection& protocol, ProtocolSpec& p) {
  if (!protocol.has("composites")) return;
  SpecDiagnostics& diag = protocol.diagnostics();
  const YAML::Node list = protocol.get("composites");
  const std::string path = protocol.child_path("composites");
  if (!list.IsSequence()) {
    diag.error(list, path, "expected a list of composites {id, items}, got " + describe_node(list));
    return;
  }
  std::set<std::string> ids;
  std::vector<std::string> scale_ids;
  for (const QuestionSpec& q : p.questions)
    if (q.kind == "scale") scale_ids.push_back(q.id);
  for (size_t i = 0; i < list.size(); ++i) {
    YamlSection c(diag, list[i], path + "[" + std::to_string(i) + "]");
    if (!c.present()) continue;
    c.allow_keys({"id", "items"});
    CompositeSpec composite;
    if (c.require("id")) {
      c.string("id", composite.id);
      bool clashes = !ids.insert(composite.id).second;
      for (const QuestionSpec& q : p.questions) clashes = clashes || q.id == composite.id;
      if (!is_identifier(composite.id))
        diag.error(c.get("id"), c.child_path("id"), "composite ids may only contain letters, digits and '_'");
      else if (clashes)
        diag.error(c.get("id"), c.child_path("id"), "id '" + composite.id + "' is already used");
    }
    if (c.require("items")) {
      c.string_list("items", composite.items);
      const YAML::Node items = c.get("items");
      if (items.IsSequence() && items.size() == 0)
        diag.error(items, c.child_path("items"), "needs at least one item");
      for (size_t k = 0; k < composite.items.size(); ++k) {
        bool found = false;
        for (const std::string& s : scale_ids) found = found || s == composite.items[k];
        if (!found)
          diag.error(items[k], c.child_path("items") + "[" + std::to_string(k) + "]",
                     "'" + composite.items[k] + "' is not a scale question" +
                         suggestion_suffix(composite.items[k], scale_ids));
      }
    }
    p.composites.push_back(composite);
  }
}

void parse_practice(YamlSection& protocol, ExperimentSpec& spec) {
  if (!protocol.has("practice")) return;
  SpecDiagnostics& diag = protocol.diagnostics();
  YamlSection practice = protocol.section("practice");
  if (!practice.present()) return;
  const std::vector<std::string> declared = factor_names(spec);
  std::set<std::string> seen;
  for (auto it = practice.node().begin(); it != practice.node().end(); ++it) {
    const std::string name = it->first.Scalar();
    const std::string path = practice.child_path(name);
    if (!seen.insert(name).second) {
      diag.error(it->first, path, "duplicate key");
      continue;
    }
    if (!spec.factor(name)) {
      diag.error(it->first, path,
                 "practice names a factor the spec does not declare" + suggestion_suffix(name, declared));
      continue;
    }
    if (auto f = parse_factor(diag, name, it->second, path)) spec.protocol.practice_factors.push_back(*f);
  }
}

/// The native study window's keys: the inter-trial screen and the video's share of the screen.
void parse_study_window(YamlSection& s, ProtocolSpec& p) {
  YamlSection iti = s.section("inter_trial");
  iti.allow_keys({"screen", "min_ms"});
  iti.choice("screen", p.inter_trial_screen);
  iti.number("min_ms", p.inter_trial_min_ms, Range::non_negative(10000.0));
  s.number("video_share", p.video_share, Range{0.0, 0.9});
  s.number("min_view_ms", p.min_view_ms, Range::non_negative(600000.0));
  if (p.video_share > 0.0 && p.video_share < 0.3)
    s.diagnostics().error(s.get("video_share"), s.child_path("video_share"),
                          "expected 0 (as large as the questions allow) or a share in [0.3, 0.9], got " +
                              format_number(p.video_share));
}

}  // namespace

void parse_protocol(YamlSection s, ExperimentSpec& spec) {
  ProtocolSpec& p = spec.protocol;
  SpecDiagnostics& diag = s.diagnostics();
  if (!s.present()) return;  // no study: crowds and stimuli only
  s.allow_keys({"type", "scale", "questions", "composites", "practice", "block_by", "block_order",
                "break_every", "instructions", "consent", "break_text", "loop_video", "completion_url",
                "inter_trial", "video_share", "min_view_ms"});
  s.choice("type", p.type);
  YamlSection scale = s.section("scale");
  scale.allow_keys({"points", "labels"});
  scale.integer("points", p.scale_points, kMinScalePoints, kMaxScalePoints);
  scale.string_list("labels", p.scale_labels);
  check_label_count(scale, "labels", p.scale_labels.size(), p.scale_points);

  parse_questions(s, p);
  if (p.type == ProtocolType::two_afc) {
    bool has_yesno = false;
    for (const QuestionSpec& q : p.questions) has_yesno = has_yesno || q.kind == "yesno";
    if (!has_yesno && s.has("questions"))
      diag.error(s.get("questions"), s.child_path("questions"),
                 "a 2afc protocol needs a question of kind: yesno");
  }
  parse_composites(s, p);
  parse_practice(s, spec);

  if (s.has("block_by")) {
    s.string("block_by", p.block_by);
    if (!p.block_by.empty() && !spec.factor(p.block_by))
      diag.error(s.get("block_by"), s.child_path("block_by"),
                 "'" + p.block_by + "' is not a factor of this spec" +
                     suggestion_suffix(p.block_by, factor_names(spec)));
  }
  s.choice("block_order", p.block_order);
  s.integer("break_every", p.break_every, 0, 100000);
  s.string("instructions", p.instructions);
  s.string("consent", p.consent);
  s.string("break_text", p.break_text);
  s.boolean("loop_video", p.loop_video);
  parse_study_window(s, p);
  if (s.has("completion_url")) {
    s.string("completion_url", p.completion_url);
    if (!is_web_url(p.completion_url))
      diag.error(s.get("completion_url"), s.child_path("completion_url"),
                 "expected an http:// or https:// URL without spaces, got '" + p.completion_url + "'");
  }
}

}  // namespace crowdlab
