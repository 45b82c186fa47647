#include "study_ui/web_import.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "crowdlab_version.hpp"
#include "framework/core/csv.hpp"
#include "framework/core/error.hpp"
#include "framework/core/sha256.hpp"
#include "study_ui/build_trial_list.hpp"
#include "study_ui/response_log.hpp"
#include "study_ui/run_session.hpp"

namespace crowdlab::study {
namespace fs = std::filesystem;
namespace {

constexpr const char* kFormat = "crowdlab-web-data";
constexpr const char* kRecordColumn = "crowdlab_record";  ///< the record's key in jsPsych's trial data

struct WebRecord {
  std::string file;
  int line = 0;  ///< line of the record's JSON value (1 when the file is one JSON document)
  nlohmann::json json;
};

[[noreturn]] void bad(const WebRecord& r, const std::string& key, const std::string& what) {
  throw InputError(SourceLocation{r.file, r.line, 0, key}, what);
}

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot read");
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// Records of one parsed JSON value (see the header for the three shapes).
void collect_records(const nlohmann::json& value, const std::string& file, int line,
                     std::vector<WebRecord>& out) {
  if (value.is_array()) {
    for (const auto& trial : value)
      if (trial.is_object() && trial.contains(kRecordColumn))
        out.push_back({file, line, trial[kRecordColumn]});
    return;
  }
  if (!value.is_object() || value.value("format", "") != kFormat)
    throw InputError(SourceLocation{file, line, 0, "format"},
                     "not crowdlab web study data (expected \"format\": \"crowdlab-web-data\")");
  if (value.contains("records")) {
    if (!value["records"].is_array())
      throw InputError(SourceLocation{file, line, 0, "records"}, "expected a list of trial records");
    for (const auto& record : value["records"]) out.push_back({file, line, record});
  } else {
    out.push_back({file, line, value});
  }
}

bool is_csv_file(const fs::path& path) {
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext == ".csv";
}

/// jsPsych's CSV data (jsPsych.data.get().csv(), JSON2CSV in jspsych/src/modules/data/utils.ts): one
/// row per jsPsych trial, one column per data key, every cell quoted, objects as JSON text. The trial
/// records are the JSON objects in the crowdlab_record column; rows with that cell empty are the
/// study's other screens.
std::vector<WebRecord> read_jspsych_csv(const std::string& path, const std::string& text) {
  const CsvTable table = parse_csv(text, path);  // names file and line for a ragged row or open quote
  if (!table.has_column(kRecordColumn))
    throw InputError(SourceLocation{path, 1, 0, kRecordColumn},
                     "not jsPsych data of a crowdlab web study (no column '" + std::string(kRecordColumn) +
                         "' in the header)");
  const size_t col = table.column(kRecordColumn);
  std::vector<WebRecord> out;
  for (size_t r = 0; r < table.rows.size(); ++r) {
    const std::string& cell = table.cell(r, col);
    if (cell.find_first_not_of(" \t") == std::string::npos) continue;
    const int line = table.line_numbers[r];
    nlohmann::json record;
    try {
      record = nlohmann::json::parse(cell);
    } catch (const nlohmann::json::parse_error& e) {
      throw InputError(SourceLocation{path, line, 0, kRecordColumn},
                       std::string("not valid JSON: ") + e.what());
    }
    if (!record.is_object())
      throw InputError(SourceLocation{path, line, 0, kRecordColumn},
                       "expected a trial record (a JSON object)");
    out.push_back({path, line, record});
  }
  return out;
}

/// One file: jsPsych CSV (*.csv), else a whole JSON document, else JSON lines.
std::vector<WebRecord> read_result_file(const std::string& path) {
  const std::string text = read_text(path);
  if (is_csv_file(path)) return read_jspsych_csv(path, text);
  std::vector<WebRecord> out;
  try {
    collect_records(nlohmann::json::parse(text), path, 1, out);
    return out;
  } catch (const nlohmann::json::parse_error&) {
  }
  std::istringstream lines(text);
  std::string line;
  int number = 0, values = 0;
  while (std::getline(lines, line)) {
    ++number;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    try {
      collect_records(nlohmann::json::parse(line), path, number, out);
      ++values;
    } catch (const nlohmann::json::parse_error& e) {
      throw InputError(SourceLocation{path, number, 0, ""}, std::string("not valid JSON: ") + e.what());
    }
  }
  if (values == 0) throw InputError(path + ": empty (no crowdlab web study data)");
  return out;
}

std::vector<std::string> result_files(const std::vector<std::string>& inputs) {
  std::vector<std::string> files;
  for (const std::string& in : inputs) {
    if (fs::is_regular_file(in)) {
      files.push_back(in);
    } else if (fs::is_directory(in)) {
      std::vector<std::string> found;
      for (const auto& e : fs::recursive_directory_iterator(in)) {
        const std::string ext = e.path().extension().string();
        if (e.is_regular_file() &&
            (ext == ".json" || ext == ".jsonl" || ext == ".txt" || is_csv_file(e.path())))
          found.push_back(e.path().string());
      }
      std::sort(found.begin(), found.end());
      if (found.empty())
        throw InputError(in + ": no result files (*.json, *.jsonl, *.txt, *.csv) in this folder");
      files.insert(files.end(), found.begin(), found.end());
    } else {
      throw InputError(SourceLocation{"", 0, 0, "RESULTS"}, in + ": no such file or folder");
    }
  }
  return files;
}

template <class T>
T field(const WebRecord& r, const std::string& key) {
  if (!r.json.is_object() || !r.json.contains(key)) bad(r, key, "the trial record lacks '" + key + "'");
  try {
    return r.json.at(key).get<T>();
  } catch (const nlohmann::json::exception&) {
    bad(r, key, "'" + key + "' has the wrong type: " + r.json.at(key).dump());
  }
}

/// The answers of a record, checked against the questions (count, order, range, rt).
std::vector<Answer> record_answers(const WebRecord& r, const std::vector<StudyQuestion>& questions) {
  const auto list = field<nlohmann::json>(r, "answers");
  if (!list.is_array() || list.size() != questions.size())
    bad(r, "answers", "expected " + std::to_string(questions.size()) + " answers, got " + list.dump());
  std::vector<Answer> out;
  for (size_t i = 0; i < questions.size(); ++i) {
    const auto& a = list[i];
    const std::string key = "answers[" + std::to_string(i) + "]";
    if (!a.is_object() || a.value("question", "") != questions[i].id)
      bad(r, key, "expected the answer to question " + questions[i].id + ", got " + a.dump());
    Answer answer;
    answer.question_id = questions[i].id;
    if (!a.contains("response") || !a["response"].is_number_integer() ||
        !questions[i].valid(a["response"].get<int>()))
      bad(r, key + ".response",
          "invalid response to " + questions[i].id + ": " + a.value("response", nlohmann::json()).dump());
    answer.raw = a["response"].get<int>();
    if (!a.contains("rt_ms") || !a["rt_ms"].is_number() || !std::isfinite(a["rt_ms"].get<double>()) ||
        a["rt_ms"].get<double>() < 0)
      bad(r, key + ".rt_ms", "expected a response time >= 0 ms");
    answer.rt_ms = a["rt_ms"].get<double>();
    answer.timestamp_utc = a.value("timestamp", "");
    out.push_back(std::move(answer));
  }
  return out;
}

struct ParticipantData {
  std::string order_of;
  std::map<int, WebRecord> by_trial;
};

struct Checked {
  std::map<std::string, ParticipantData> participants;
  int records = 0, merged = 0;
};

Checked check_records(const ExperimentSpec& spec, const StimulusManifest& manifest,
                      const std::vector<WebRecord>& records, const std::vector<StudyQuestion>& questions) {
  std::map<std::string, const StimulusEntry*> stimuli;
  for (const StimulusEntry& e : manifest.entries) stimuli[e.id] = &e;
  std::map<std::string, std::vector<Trial>> orders;
  Checked out;
  for (const WebRecord& r : records) {
    ++out.records;
    if (field<std::string>(r, "spec_hash") != spec.source_hash)
      bad(r, "spec_hash",
          "recorded with another spec (sha256 " + field<std::string>(r, "spec_hash") + ", this spec's is " +
              spec.source_hash + ")");
    const auto participant = field<std::string>(r, "participant");
    const auto order_of = field<std::string>(r, "order_of");
    try {
      check_participant_id(participant);
      check_participant_id(order_of);
    } catch (const InputError& e) {
      bad(r, "participant", e.what());
    }
    if (!orders.count(order_of))
      orders[order_of] = build_trial_list(spec.protocol, manifest, spec.seed, order_of);
    const std::vector<Trial>& order = orders[order_of];
    const int trial = field<int>(r, "trial");
    if (trial < 1 || trial > static_cast<int>(order.size()))
      bad(r, "trial", "trial " + std::to_string(trial) + " is outside 1.." + std::to_string(order.size()));
    const Trial& expected = order[static_cast<size_t>(trial - 1)];
    const auto stimulus = field<std::string>(r, "stimulus");
    if (stimulus != expected.stimulus.id || field<std::string>(r, "block") != expected.block ||
        field<bool>(r, "practice") != expected.practice)
      bad(r, "stimulus",
          "trial " + std::to_string(trial) + " shows '" + stimulus + "' but the order of " + order_of +
              " has '" + expected.stimulus.id + "' (block " + expected.block + ") there");
    const std::string sha = field<std::string>(r, "stimulus_sha256");
    if (!expected.stimulus.sha256.empty() && sha != expected.stimulus.sha256)
      bad(r, "stimulus_sha256",
          stimulus + ": the clip shown (sha256 " + sha + ") is not the manifest's (" +
              expected.stimulus.sha256 + ")");
    if (field<int>(r, "session") < 1) bad(r, "session", "expected a session number >= 1");
    record_answers(r, questions);

    ParticipantData& p = out.participants[participant];
    if (p.order_of.empty()) p.order_of = order_of;
    if (p.order_of != order_of)
      bad(r, "order_of",
          participant + " ran the order of " + order_of + " here and of " + p.order_of + " elsewhere");
    auto [it, inserted] = p.by_trial.emplace(trial, r);
    if (!inserted) {
      if (it->second.json != r.json)
        bad(r, "trial",
            participant + " answered trial " + std::to_string(trial) + " differently in " + it->second.file +
                ":" + std::to_string(it->second.line) + "; refusing to choose");
      ++out.merged;
    }
  }
  return out;
}

std::string participant_csv(const ExperimentSpec& spec, const StimulusManifest& manifest,
                            const std::string& id, const ParticipantData& p,
                            const std::vector<StudyQuestion>& questions) {
  const std::vector<Trial> order = build_trial_list(spec.protocol, manifest, spec.seed, p.order_of);
  std::string text = csv_line(response_header(manifest.factor_names));
  for (const auto& [trial, record] : p.by_trial) {
    const auto rows = response_rows(id, field<int>(record, "session"), order[static_cast<size_t>(trial - 1)],
                                    manifest.factor_names, questions, record_answers(record, questions));
    for (const auto& row : rows) text += csv_line(row);
  }
  return text;
}

nlohmann::json participant_metadata(const ExperimentSpec& spec, const std::string& id,
                                    const ParticipantData& p, const std::vector<StudyQuestion>& questions,
                                    size_t trials, const std::string& manifest_sha256) {
  nlohmann::json meta = {{"participant", id},
                         {"source", "web"},
                         {"order_of", p.order_of},
                         {"spec_name", spec.name},
                         {"spec_path", spec.source_path},
                         {"spec_hash", spec.source_hash},
                         {"spec_seed", spec.seed},
                         {"participant_seed", participant_seed(spec.seed, p.order_of)},
                         {"crowdlab_version", CROWDLAB_VERSION},
                         {"protocol", kind_name(spec.protocol.type)},
                         {"trials", trials},
                         {"trials_done", p.by_trial.size()},
                         {"manifest_sha256", manifest_sha256},
                         {"status", p.by_trial.size() == trials ? "complete" : "incomplete"},
                         {"questions", nlohmann::json::array()},
                         {"video", nlohmann::json::array()}};
  for (const auto& q : questions) meta["questions"].push_back({{"id", q.id}, {"reverse", q.reverse}});
  for (const auto& [trial, r] : p.by_trial)
    meta["video"].push_back({{"trial", trial},
                             {"session", r.json.value("session", 0)},
                             {"timing", r.json.value("video", nlohmann::json())}});
  return meta;
}

}  // namespace

WebImportResult import_web(const ExperimentSpec& spec, const StimulusManifest& manifest,
                           const std::vector<std::string>& inputs, const WebImportOptions& opt) {
  const std::vector<StudyQuestion> questions = resolve_questions(spec.protocol);
  WebImportResult result;
  std::vector<WebRecord> records;
  for (const std::string& file : result_files(inputs)) {
    auto some = read_result_file(file);
    records.insert(records.end(), some.begin(), some.end());
    ++result.files;
  }
  if (records.empty()) throw InputError("no trial records in the given results");
  const Checked checked = check_records(spec, manifest, records, questions);
  result.records = checked.records;
  result.duplicates_merged = checked.merged;

  const std::string manifest_csv = (fs::path(opt.stimuli_dir) / "manifest.csv").string();
  const std::string manifest_sha = fs::exists(manifest_csv) ? sha256_file_hex(manifest_csv) : "";
  std::map<std::string, std::string> csv_text;
  for (const auto& [id, p] : checked.participants) {
    csv_text[id] = participant_csv(spec, manifest, id, p, questions);
    const fs::path csv = fs::path(opt.out_dir) / (id + ".csv");
    if (fs::exists(csv) && read_text(csv.string()) != csv_text[id])
      throw InputError(
          SourceLocation{"", 0, 0, "--out"},
          csv.string() + ": already holds other answers of participant " + id +
              " (a native session, or an earlier import of different data); refusing to overwrite");
  }
  fs::create_directories(opt.out_dir);
  for (const auto& [id, p] : checked.participants) {
    const fs::path csv = fs::path(opt.out_dir) / (id + ".csv");
    ++result.participants;
    const size_t trials = build_trial_list(spec.protocol, manifest, spec.seed, p.order_of).size();
    if (p.by_trial.size() == trials) ++result.complete;
    result.csv_paths.push_back(csv.string());
    if (fs::exists(csv)) {
      ++result.already_imported;
      continue;
    }
    write_file_atomically(csv.string(), csv_text[id]);
    const nlohmann::json meta = participant_metadata(spec, id, p, questions, trials, manifest_sha);
    write_file_atomically((fs::path(opt.out_dir) / (id + ".json")).string(), meta.dump(2) + "\n");
  }
  return result;
}

}  // namespace crowdlab::study
