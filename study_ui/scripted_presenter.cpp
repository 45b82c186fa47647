#include "study_ui/scripted_presenter.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <thread>

#include "framework/core/csv.hpp"
#include "framework/core/error.hpp"

namespace crowdlab::study {

ScriptedPresenter::ScriptedPresenter(const std::string& csv_path, int delay_ms)
    : path_(csv_path), delay_ms_(std::max(0, delay_ms)) {
  const CsvTable t = read_csv(csv_path);
  const size_t s = t.column("stimulus"), q = t.column("question"), r = t.column("response");
  const bool has_rt = t.has_column("rt_ms");
  for (size_t i = 0; i < t.rows.size(); ++i) {
    Entry e;
    e.response = t.cell(i, r);
    e.line = t.line_numbers[i];
    if (has_rt && !t.cell(i, t.column("rt_ms")).empty()) {
      e.rt_ms = t.number(i, t.column("rt_ms"));
      if (e.rt_ms < 0)
        throw InputError(SourceLocation{csv_path, e.line, 0, "rt_ms"}, "negative response time");
    }
    if (!answers_.emplace(std::make_pair(t.cell(i, s), t.cell(i, q)), e).second)
      throw InputError(SourceLocation{csv_path, e.line, 0, "stimulus,question"},
                       "duplicate answer for " + t.cell(i, s) + " / " + t.cell(i, q));
  }
}

bool ScriptedPresenter::parse_response(const StudyQuestion& q, const std::string& text, int& raw) {
  std::string t = text;
  std::transform(t.begin(), t.end(), t.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (q.kind == QuestionKind::yesno) {
    if (t == "yes" || t == "y" || t == "1") return raw = 1, true;
    if (t == "no" || t == "n" || t == "0") return raw = 0, true;
    return false;
  }
  if (t.empty() || t.size() > 3 ||
      !std::all_of(t.begin(), t.end(), [](char c) { return c >= '0' && c <= '9'; }))
    return false;
  raw = std::stoi(t);
  return q.valid(raw);
}

void ScriptedPresenter::check(const StimulusManifest& manifest,
                              const std::vector<StudyQuestion>& questions) const {
  std::vector<std::string> problems;
  for (const StimulusEntry& e : manifest.entries)
    for (const StudyQuestion& q : questions) {
      auto it = answers_.find({e.id, q.id});
      int raw = 0;
      if (it == answers_.end())
        problems.push_back("no answer for stimulus " + e.id + ", question " + q.id);
      else if (!parse_response(q, it->second.response, raw))
        problems.push_back("line " + std::to_string(it->second.line) + ": '" + it->second.response +
                           "' is not a valid answer to " + q.id);
    }
  if (problems.empty()) return;
  std::string msg = path_ + ": the scripted responses do not cover the session (" +
                    std::to_string(problems.size()) + " problem(s)):";
  for (size_t i = 0; i < problems.size() && i < 20; ++i) msg += "\n  " + problems[i];
  throw InputError(msg);
}

ScreenReply ScriptedPresenter::show_screen(const PlanScreen& screen) {
  transcript_.push_back({{"screen", screen_kind_name(screen.kind)},
                         {"title", screen.title},
                         {"text", screen.text},
                         {"hint", screen.hint}});
  return ScreenReply::proceed;
}

TrialOutcome ScriptedPresenter::run_trial(const TrialRequest& request) {
  transcript_.push_back({{"inter_trial", kind_name(request.inter_trial_screen)}});
  transcript_.push_back({{"trial", request.trial->index}, {"header", request.header}});
  const auto onset = std::chrono::steady_clock::now();
  if (delay_ms_ > 0) std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms_));
  TrialOutcome out;
  for (const StudyQuestion& q : *request.questions) {
    auto it = answers_.find({request.trial->stimulus.id, q.id});
    Answer a;
    a.question_id = q.id;
    if (it == answers_.end() || !parse_response(q, it->second.response, a.raw))
      throw InputError(path_ + ": no valid answer for stimulus " + request.trial->stimulus.id +
                       ", question " + q.id);
    a.rt_ms =
        it->second.rt_ms >= 0
            ? it->second.rt_ms
            : std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - onset).count();
    a.timestamp_utc = iso8601_utc_now();
    out.answers.push_back(std::move(a));
  }
  return out;
}

}  // namespace crowdlab::study
