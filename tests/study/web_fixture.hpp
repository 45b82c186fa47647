#pragma once
// Shared by the web study tests (test_web.cpp, test_web_csv.cpp): scripted answers, the native scripted
// session of an id, what the web page stores for a participant (its localStorage dump), and jsPsych's
// data of it as JSON trials and as jsPsych's CSV.
#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "framework/core/csv.hpp"
#include "study_ui/run_session.hpp"
#include "study_ui/scripted_presenter.hpp"
#include "study_ui/web_export.hpp"
#include "tests/study/study_fixture.hpp"

namespace crowdlab::test::web {
namespace fs = std::filesystem;
using namespace crowdlab::study;

/// Answers for every (stimulus, question): raw = 1 + (k mod points), yes/no k mod 2. `participant` 0 (the
/// web participant) has k = n, the running number of the answer. Others (lab participants beside it in a
/// report) have a hashed k (Knuth's multiplicative hash of n and the participant, high bits folded in),
/// so that no two participants' differences between cells agree and every ANOVA effect has error
/// variance (a shift of n by a participant-dependent amount left one effect without any).
inline std::map<std::pair<std::string, std::string>, int> scripted_answers(
    const StimulusManifest& m, const std::vector<StudyQuestion>& qs, int participant = 0) {
  std::map<std::pair<std::string, std::string>, int> out;
  int n = 0;
  for (const auto& e : m.entries)
    for (const auto& q : qs) {
      std::uint32_t h = (static_cast<std::uint32_t>(n) + 1u) * 2654435761u ^
                        static_cast<std::uint32_t>(participant) * 2246822519u;
      h ^= h >> 15;
      const int k = participant == 0 ? n : static_cast<int>(h % 997u);
      out[{e.id, q.id}] = q.kind == QuestionKind::yesno ? k % 2 : 1 + k % q.points;
      ++n;
    }
  return out;
}

inline fs::path write_script(const fs::path& path,
                             const std::map<std::pair<std::string, std::string>, int>& answers,
                             const std::vector<StudyQuestion>& qs) {
  std::ofstream out(path);
  out << "stimulus,question,response,rt_ms\n";
  for (const auto& [key, raw] : answers) {
    const bool yesno = std::any_of(qs.begin(), qs.end(), [&](const auto& q) {
      return q.id == key.second && q.kind == QuestionKind::yesno;
    });
    out << key.first << "," << key.second << "," << (yesno ? (raw ? "yes" : "no") : std::to_string(raw))
        << ",750\n";
  }
  return path;
}

/// A native scripted session's P.csv for `id`.
inline std::string native_csv(const ExperimentSpec& spec, const StimulusManifest& m, const fs::path& stimuli,
                              const fs::path& script, const fs::path& out, const std::string& id) {
  ScriptedPresenter presenter(script.string(), 0);
  SessionOptions opt{id, stimuli.string(), out.string(), false, "scripted", true, false};
  return run_session(spec, m, opt, presenter).csv_path;
}

/// What the web study stores for one participant (crowdlab_study.js's AnswerStore), built from the
/// timeline's order and the answers; rt 750 ms like the script.
inline nlohmann::json web_dump(const nlohmann::json& timeline, const std::string& participant,
                               const std::map<std::pair<std::string, std::string>, int>& answers) {
  const std::string order_of = web_order_participant(participant, timeline["order_ids"]);
  nlohmann::json dump = {{"format", "crowdlab-web-data"},
                         {"participant", participant},
                         {"order_of", order_of},
                         {"records", nlohmann::json::array()}};
  for (const auto& t : timeline["orders"][order_of]) {
    nlohmann::json record = {
        {"format", "crowdlab-web-data"},
        {"participant", participant},
        {"order_of", order_of},
        {"session", 1},
        {"spec_hash", timeline["study"]["spec_hash"]},
        {"trial", t["trial"]},
        {"stimulus", t["stimulus"]},
        {"stimulus_sha256", timeline["stimuli"][t["stimulus"].get<std::string>()]["sha256"]},
        {"block", t["block"]},
        {"practice", t["practice"]},
        {"answers", nlohmann::json::array()}};
    for (const auto& q : timeline["questions"])
      record["answers"].push_back({{"question", q["id"]},
                                   {"response", answers.at({t["stimulus"], q["id"]})},
                                   {"rt_ms", 750},
                                   {"timestamp", "2026-11-25T03:00:00.000Z"}});
    dump["records"].push_back(record);
  }
  return dump;
}

/// A CSV's rows without the columns that legitimately differ between two runs of the same answers.
inline std::vector<std::vector<std::string>> comparable_rows(const std::string& csv_path,
                                                             const std::vector<std::string>& ignore) {
  const CsvTable t = read_csv(csv_path);
  std::vector<std::vector<std::string>> out;
  for (size_t r = 0; r < t.rows.size(); ++r) {
    std::vector<std::string> row;
    for (size_t c = 0; c < t.header.size(); ++c)
      if (std::find(ignore.begin(), ignore.end(), t.header[c]) == ignore.end()) row.push_back(t.cell(r, c));
    out.push_back(row);
  }
  return out;
}

inline ExperimentSpec blocked_spec(BlockOrder block_order) {
  ExperimentSpec spec = test::likert_spec();
  spec.protocol.block_by = "density";
  spec.protocol.block_order = block_order;
  spec.protocol.break_every = 3;
  return spec;
}

inline void write_json(const fs::path& path, const nlohmann::json& j) {
  std::ofstream(path) << j.dump() << "\n";
}

/// A cell of jsPsych's CSV: always quoted, " doubled.
inline std::string jspsych_quoted(const std::string& text) {
  std::string out = "\"";
  for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

/// jsPsych's CSV of a data array, as jsPsych.data.get().csv() writes it (JSON2CSV in
/// jspsych/src/modules/data/utils.ts): the union of the keys in order of appearance, every cell
/// quoted, objects as JSON text, CRLF line ends.
inline std::string jspsych_csv(const nlohmann::ordered_json& trials) {
  std::vector<std::string> columns;
  for (const auto& t : trials)
    for (const auto& [key, value] : t.items())
      if (std::find(columns.begin(), columns.end(), key) == columns.end()) columns.push_back(key);
  const auto quoted = jspsych_quoted;
  std::string csv;
  for (size_t c = 0; c < columns.size(); ++c) csv += (c ? "," : "") + quoted(columns[c]);
  csv += "\r\n";
  for (const auto& t : trials) {
    for (size_t c = 0; c < columns.size(); ++c) {
      std::string cell;
      if (t.contains(columns[c])) {
        const auto& v = t[columns[c]];
        cell = v.is_string() ? v.get<std::string>() : v.dump();
      }
      csv += (c ? "," : "") + quoted(cell);
    }
    csv += "\r\n";
  }
  return csv;
}

/// A jsPsych data array around the records of a dump: a full-screen row before, a text screen whose
/// stimulus has commas, quotes and a line break after every record (so the CSV has multi-line cells).
inline nlohmann::ordered_json jspsych_trials(const nlohmann::json& dump) {
  nlohmann::ordered_json trials = nlohmann::ordered_json::array();
  trials.push_back({{"rt", 812}, {"trial_type", "fullscreen"}, {"success", true}});
  for (const auto& rec : dump["records"]) {
    trials.push_back({{"rt", 4711},
                      {"response", {{"Q1", 2}}},
                      {"trial_type", "survey-likert"},
                      {"crowdlab_record", nlohmann::ordered_json::parse(rec.dump())}});
    trials.push_back({{"rt", 300},
                      {"stimulus", "<h2>Break</h2><p>Rest, then press \"any\" key.\nThanks</p>"},
                      {"trial_type", "html-keyboard-response"}});
  }
  return trials;
}

}  // namespace crowdlab::test::web
