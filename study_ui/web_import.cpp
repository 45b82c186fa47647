#include "study_ui/web_import.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <sstream>
#include <type_traits>

#include "crowdlab_version.hpp"
#include "framework/core/csv.hpp"
#include "framework/core/error.hpp"
#include "framework/core/file_kind.hpp"
#include "framework/core/sha256.hpp"
#include "framework/io/untrusted_json.hpp"
#include "study_ui/build_trial_list.hpp"
#include "study_ui/frame_interval_stats.hpp"
#include "study_ui/participant_id.hpp"
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

/// The limits of untrusted_json.hpp for a participant's records (a record nests 4 levels).
JsonLimits web_json_limits(const WebImportOptions& opt) {
  JsonLimits limits;
  limits.max_depth = 32;
  limits.max_bytes = opt.max_file_bytes;
  limits.raise_with = "--max-file-mb";
  return limits;
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
    if (value.contains("consent_record")) out.push_back({file, line, value["consent_record"]});
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
std::vector<WebRecord> read_jspsych_csv(const std::string& path, const std::string& text,
                                        const JsonLimits& limits) {
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
      record = parse_untrusted_json(cell, path, limits, 0, line);
    } catch (const InputError& e) {
      throw InputError(SourceLocation{path, line, 0, kRecordColumn},
                       std::string("the record cell: ") + e.what());
    }
    if (!record.is_object())
      throw InputError(SourceLocation{path, line, 0, kRecordColumn},
                       "expected a trial record (a JSON object)");
    out.push_back({path, line, record});
  }
  return out;
}

/// One file: jsPsych CSV (*.csv), else a whole JSON document, else JSON lines.
std::vector<WebRecord> read_result_file(const std::string& path, const JsonLimits& limits) {
  // Size from stat before reading; FIFOs and devices refused before opening (issue 32).
  const std::string text = read_regular_file(path, "web results", limits.max_bytes, limits.raise_with);
  if (is_csv_file(path)) return read_jspsych_csv(path, text, limits);
  check_untrusted_json(text, path, limits);  // depth: the whole text, before either parse below
  std::vector<WebRecord> out;
  if (nlohmann::json whole = nlohmann::json::parse(text, nullptr, false); !whole.is_discarded()) {
    collect_records(whole, path, 1, out);
    return out;
  }
  int number = 0, values = 0;
  for (size_t start = 0; start < text.size();) {
    const size_t end = std::min(text.find('\n', start), text.size());
    const std::string_view line(text.data() + start, end - start);
    const size_t offset = start;
    start = end + 1;
    ++number;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    collect_records(parse_untrusted_json(line, path, limits, offset, number), path, number, out);
    ++values;
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
        if (e.is_directory() ||
            !(ext == ".json" || ext == ".jsonl" || ext == ".txt" || is_csv_file(e.path())))
          continue;
        require_regular_input(e.path(), "web results");  // a FIFO named *.json: refused, never opened
        found.push_back(e.path().string());
      }
      std::sort(found.begin(), found.end());
      if (found.empty())
        throw InputError(in + ": no result files (*.json, *.jsonl, *.txt, *.csv) in this folder");
      files.insert(files.end(), found.begin(), found.end());
    } else if (fs::exists(in)) {
      require_regular_input(in, "web results");  // a FIFO or device: refused, never opened
    } else {
      throw InputError(SourceLocation{"", 0, 0, "RESULTS"}, in + ": no such file or folder");
    }
  }
  return files;
}

/// `value` as an int when it is a JSON integer in int's range; nlohmann's get<int>() narrows silently
/// (issue 33: response 4294967299 was stored as 3, trial 4294967298 as 2).
std::optional<int> int_in_range(const nlohmann::json& value) {
  if (value.is_number_unsigned())
    return value.get<std::uint64_t>() <= static_cast<std::uint64_t>(std::numeric_limits<int>::max())
               ? std::optional<int>(static_cast<int>(value.get<std::uint64_t>()))
               : std::nullopt;
  if (!value.is_number_integer()) return std::nullopt;
  const std::int64_t v = value.get<std::int64_t>();
  if (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max()) return std::nullopt;
  return static_cast<int>(v);
}

/// A value cut for a message (a hostile value may be megabytes long).
std::string quoted(const nlohmann::json& value) {
  const std::string text = value.dump();
  return text.size() <= 80 ? text
                           : text.substr(0, 80) + "... (" + std::to_string(text.size() - 80) + " more)";
}

template <class T>
T field(const WebRecord& r, const std::string& key) {
  if (!r.json.is_object() || !r.json.contains(key)) bad(r, key, "the trial record lacks '" + key + "'");
  if constexpr (std::is_same_v<T, int>) {
    if (const auto v = int_in_range(r.json.at(key))) return *v;
    bad(r, key, "'" + key + "' must be a whole number in int's range, got " + quoted(r.json.at(key)));
  } else {
    try {
      return r.json.at(key).get<T>();
    } catch (const nlohmann::json::exception&) {
      bad(r, key, "'" + key + "' has the wrong type: " + quoted(r.json.at(key)));
    }
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
    const std::optional<int> response = a.contains("response") ? int_in_range(a["response"]) : std::nullopt;
    if (!response || !questions[i].valid(*response))
      bad(r, key + ".response",
          "invalid response to " + questions[i].id + ": " + quoted(a.value("response", nlohmann::json())));
    answer.raw = *response;
    if (!a.contains("rt_ms") || !a["rt_ms"].is_number() || !std::isfinite(a["rt_ms"].get<double>()) ||
        a["rt_ms"].get<double>() < 0)
      bad(r, key + ".rt_ms", "expected a response time >= 0 ms");
    answer.rt_ms = a["rt_ms"].get<double>();
    answer.timestamp_utc = a.value("timestamp", "");
    out.push_back(std::move(answer));
  }
  return out;
}

/// A consent record (the page writes one when the consent screen is answered): {"format", "kind":
/// "consent", "participant", "order_of", "spec_hash", "consent": {"given", "utc", "session"}}.
bool is_consent_record(const WebRecord& r) {
  return r.json.is_object() && r.json.value("kind", "") == "consent";
}

struct ParticipantData {
  std::string order_of;
  std::map<int, WebRecord> by_trial;
  std::optional<WebRecord> consent;
  bool declined() const { return consent && !consent->json["consent"]["given"].get<bool>(); }
};

/// An input that is not imported: the participant it concerns ("" when the file names none) and why,
/// with file, line and key.
struct Problem {
  std::string participant;
  std::string text;
  std::string file;  ///< where (for collapsing one participant's repeated problems in one file)
};

struct Checked {
  std::map<std::string, ParticipantData> participants;
  std::vector<Problem> problems;
  int records = 0, merged = 0;
};

/// The participant a record names, when it names one as a string ("" otherwise).
std::string named_participant(const WebRecord& r) {
  if (r.json.is_object() && r.json.contains("participant") && r.json["participant"].is_string())
    return r.json["participant"].get<std::string>();
  return "";
}

/// Keeps `r` as the participant's record for `slot` (a trial, or the consent); an identical copy is
/// merged, a different one refused.
void keep_once(std::optional<WebRecord>& slot, const WebRecord& r, const std::string& what, int& merged) {
  if (!slot) {
    slot = r;
    return;
  }
  if (slot->json != r.json)
    bad(r, what,
        named_participant(r) + " answered " + what + " differently in " + slot->file + ":" +
            std::to_string(slot->line) + "; refusing to choose");
  ++merged;
}

void check_consent(const WebRecord& r, ParticipantData& p, int& merged) {
  const auto c = field<nlohmann::json>(r, "consent");
  if (!c.is_object() || !c.contains("given") || !c["given"].is_boolean() || !c.contains("utc") ||
      !c["utc"].is_string() || !c.contains("session") || !c["session"].is_number_integer())
    bad(r, "consent", "expected {\"given\": true or false, \"utc\": time, \"session\": n}, got " + c.dump());
  keep_once(p.consent, r, "consent", merged);
}

/// One record's checks (spec, ids, order, stimulus, answers); adds it to its participant.
void check_record(const ExperimentSpec& spec, const StimulusManifest& manifest, const WebRecord& r,
                  const std::vector<StudyQuestion>& questions,
                  std::map<std::string, std::vector<Trial>>& orders, Checked& out) {
  if (field<std::string>(r, "spec_hash") != spec.source_hash)
    bad(r, "spec_hash",
        "recorded with another spec (sha256 " + field<std::string>(r, "spec_hash") + ", this spec's is " +
            spec.source_hash + ")");
  const auto participant = field<std::string>(r, "participant");
  const auto order_of = field<std::string>(r, "order_of");
  if (!valid_participant_id(participant))
    bad(r, "participant", "participant id '" + participant + "' " + kParticipantIdRule);
  if (!valid_participant_id(order_of)) bad(r, "order_of", "id '" + order_of + "' " + kParticipantIdRule);
  if (!orders.count(order_of))
    orders[order_of] = build_trial_list(spec.protocol, manifest, spec.seed, order_of);
  auto check_order_of = [&](ParticipantData& p) {
    if (p.order_of.empty()) p.order_of = order_of;
    if (p.order_of != order_of)
      bad(r, "order_of",
          participant + " ran the order of " + order_of + " here and of " + p.order_of + " elsewhere");
  };
  if (is_consent_record(r)) {
    ParticipantData& p = out.participants[participant];
    check_order_of(p);
    check_consent(r, p, out.merged);
    return;
  }
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
  check_order_of(p);
  std::optional<WebRecord> slot;
  if (auto it = p.by_trial.find(trial); it != p.by_trial.end()) slot = it->second;
  keep_once(slot, r, "trial " + std::to_string(trial), out.merged);
  p.by_trial.insert_or_assign(trial, *slot);
}

/// Every record checked on its own: a record that fails is a problem of its participant (who is then
/// not imported), never of the others.
Checked check_records(const ExperimentSpec& spec, const StimulusManifest& manifest,
                      const std::vector<WebRecord>& records, const std::vector<StudyQuestion>& questions) {
  std::map<std::string, std::vector<Trial>> orders;
  std::map<std::ptrdiff_t, int> repeats;  // problem index -> further failing records
  Checked out;
  for (const WebRecord& r : records) {
    ++out.records;
    try {
      check_record(spec, manifest, r, questions, orders, out);
    } catch (const InputError& e) {
      // One line per participant and file: the first problem, and how many records share its fate.
      const std::string who = named_participant(r);
      auto same = std::find_if(out.problems.begin(), out.problems.end(), [&](const Problem& p) {
        return !who.empty() && p.participant == who && p.file == r.file;
      });
      if (same == out.problems.end())
        out.problems.push_back({who, e.what(), r.file});
      else
        ++repeats[&*same - &out.problems[0]];
    }
  }
  for (const auto& [index, n] : repeats)
    out.problems[index].text += " (and " + std::to_string(n) + " more record(s) of " +
                                out.problems[index].participant + " in this file)";
  for (const auto& [id, p] : out.participants)
    if (p.declined() && !p.by_trial.empty())
      out.problems.push_back({id,
                              p.consent->file + ":" + std::to_string(p.consent->line) + ": " + id +
                                  " declined consent but has " + std::to_string(p.by_trial.size()) +
                                  " answered trial(s); refusing to import either",
                              p.consent->file});
  return out;
}

/// The presentation timing of a record's clip, as the native columns hold it (empty when the page
/// measured none): onset, inter-trial gap, frames presented and dropped, and the intervals between
/// the presented frames (frame_interval_stats of their display times, as natively).
TrialTiming record_timing(const WebRecord& r) {
  TrialTiming t;
  const nlohmann::json v = r.json.value("video", nlohmann::json());
  if (!v.is_object() || !v.contains("onset_utc") || !v["onset_utc"].is_string()) return t;
  t.onset_utc = v["onset_utc"].get<std::string>();
  auto number = [&](const char* key, double fallback) {
    return v.contains(key) && v[key].is_number() ? v[key].get<double>() : fallback;
  };
  t.inter_trial_ms = number("inter_trial_ms", -1.0);
  t.frames_shown = static_cast<long>(number("frames_presented", 0.0));
  t.frames_dropped = static_cast<long>(number("frames_dropped", 0.0));
  if (v.contains("frame_times_ms") && v["frame_times_ms"].is_array()) {
    std::vector<double> times;
    for (const auto& x : v["frame_times_ms"])
      if (x.is_number()) times.push_back(x.get<double>());
    t.intervals = frame_interval_stats(times);
  }
  return t;
}

std::string participant_csv(const ExperimentSpec& spec, const StimulusManifest& manifest,
                            const std::string& id, const ParticipantData& p,
                            const std::vector<StudyQuestion>& questions) {
  const std::vector<Trial> order = build_trial_list(spec.protocol, manifest, spec.seed, p.order_of);
  std::string text = csv_line(response_header(manifest.factor_names));
  for (const auto& [trial, record] : p.by_trial) {
    const auto rows = response_rows(id, field<int>(record, "session"), order[static_cast<size_t>(trial - 1)],
                                    manifest.factor_names, questions, record_answers(record, questions),
                                    false, record_timing(record));
    for (const auto& row : rows) text += csv_line(row);
  }
  return text;
}

nlohmann::json participant_metadata(const ExperimentSpec& spec, const std::string& id,
                                    const ParticipantData& p, const std::vector<StudyQuestion>& questions,
                                    size_t trials, const std::string& manifest_sha256) {
  const std::string status = p.declined()                  ? "declined"
                             : p.by_trial.size() == trials ? "complete"
                                                           : "incomplete";
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
                         {"status", status},
                         {"questions", nlohmann::json::array()},
                         {"video", nlohmann::json::array()}};
  // The native session's consent object, field for field (run_session.cpp).
  if (p.consent) meta["consent"] = p.consent->json["consent"];
  for (const auto& q : questions) meta["questions"].push_back({{"id", q.id}, {"reverse", q.reverse}});
  for (const auto& [trial, r] : p.by_trial)
    meta["video"].push_back({{"trial", trial},
                             {"session", r.json.value("session", 0)},
                             {"timing", r.json.value("video", nlohmann::json())}});
  return meta;
}

/// An import never replaces a participant's files (issue 32: an import for W01 replaced the W01.json of
/// an earlier session and exited 0). The participant in the folder is the same one only when its P.csv
/// holds byte for byte the records imported now; a P.json without that P.csv, a P.csv with other
/// records, or either one not a regular file is refused, naming the file in the folder and the record's.
void check_existing_participant(const std::string& out_dir, const std::string& id,
                                const std::string& csv_text, const WebRecord& first) {
  const fs::path csv = fs::path(out_dir) / (id + ".csv");
  const fs::path json = fs::path(out_dir) / (id + ".json");
  const std::string imported = first.file + ":" + std::to_string(first.line);
  const auto refuse = [&](const fs::path& existing, const std::string& why) {
    throw InputError(SourceLocation{"", 0, 0, "--out"},
                     existing.string() + ": " + why + " of participant " + id + " than the records in " +
                         imported + "; refusing to overwrite (import into another folder, or rename one)");
  };
  for (const fs::path& p : {csv, json}) {
    const std::string kind = describe_file_kind(p, false);
    if (!kind.empty() && kind != "missing")
      throw InputError(SourceLocation{"", 0, 0, "--out"}, p.string() + ": is " + kind +
                                                              ", not a participant file; refusing to write " +
                                                              id + " (records in " + imported + ")");
  }
  if (fs::exists(csv) && read_text(csv.string()) != csv_text)
    refuse(csv, "already holds other answers (a native session, or an earlier import of different data)");
  if (!fs::exists(csv) && fs::exists(json)) refuse(json, "already holds the metadata of another session");
}

/// One participant's files to write.
struct Output {
  std::string id;
  std::string csv_text;
  std::string json_text;
  bool already_there = false;  ///< an identical P.csv is in the output folder
  bool complete = false;
};

std::string problems_text(const std::vector<Problem>& problems) {
  std::string text;
  for (const Problem& p : problems) text += "\n  " + p.text;
  return text;
}

}  // namespace

WebImportResult import_web(const ExperimentSpec& spec, const StimulusManifest& manifest,
                           const std::vector<std::string>& inputs, const WebImportOptions& opt) {
  const std::vector<StudyQuestion> questions = resolve_questions(spec.protocol);
  WebImportResult result;
  std::vector<WebRecord> records;
  std::vector<Problem> file_problems;
  for (const std::string& file : result_files(inputs)) {
    ++result.files;
    try {
      auto some = read_result_file(file, web_json_limits(opt));
      records.insert(records.end(), some.begin(), some.end());
    } catch (const InputError& e) {
      file_problems.push_back({"", e.what(), file});
    }
  }
  if (records.empty() && file_problems.empty()) throw InputError("no trial records in the given results");
  Checked checked = check_records(spec, manifest, records, questions);
  checked.problems.insert(checked.problems.begin(), file_problems.begin(), file_problems.end());
  result.records = checked.records;
  result.duplicates_merged = checked.merged;
  std::set<std::string> refused;
  for (const Problem& p : checked.problems)
    if (!p.participant.empty()) refused.insert(p.participant);

  const std::string manifest_csv = (fs::path(opt.stimuli_dir) / "manifest.csv").string();
  const std::string manifest_sha = fs::exists(manifest_csv) ? sha256_file_hex(manifest_csv) : "";
  // Ids differing only in case within these results: one participant twice, or two people; neither
  // is imported (a human decides), as the native study refuses the second.
  std::map<std::string, std::vector<std::string>> by_folded;
  for (const auto& [id, p] : checked.participants) {
    if (refused.count(id)) continue;
    std::string lower = id;
    for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    by_folded[lower].push_back(id);
  }
  for (const auto& [lower, ids] : by_folded)
    for (size_t i = 0; ids.size() > 1 && i < ids.size(); ++i) {
      refused.insert(ids[i]);
      checked.problems.push_back({ids[i],
                                  "participant '" + ids[i] + "' clashes with '" + ids[(i + 1) % ids.size()] +
                                      "' in these results: ids differing only in case are one participant",
                                  ""});
    }
  std::vector<Output> outputs;
  for (const auto& [id, p] : checked.participants) {
    if (refused.count(id)) continue;
    auto refuse = [&](const std::string& why) { checked.problems.push_back({id, why, ""}); };
    if (const auto other = case_clash(opt.out_dir, id)) {
      refuse("participant '" + id + "' clashes with '" + *other + "' in " + opt.out_dir +
             ": ids differing only in case are one participant");
      continue;
    }
    Output o;
    o.id = id;
    o.csv_text = participant_csv(spec, manifest, id, p, questions);
    const fs::path csv = fs::path(opt.out_dir) / (id + ".csv");
    try {
      check_existing_participant(opt.out_dir, id, o.csv_text, p.by_trial.begin()->second);
    } catch (const InputError& e) {
      refuse(e.what());
      continue;
    }
    o.already_there = fs::exists(csv);  // byte for byte the records imported now (checked above)
    const size_t trials = build_trial_list(spec.protocol, manifest, spec.seed, p.order_of).size();
    o.complete = p.by_trial.size() == trials;
    o.json_text = participant_metadata(spec, id, p, questions, trials, manifest_sha).dump(2) + "\n";
    if (p.declined()) ++result.declined;
    outputs.push_back(std::move(o));
  }
  for (const Problem& p : checked.problems) result.problems.push_back(p.text);

  if (outputs.empty())
    throw InputError("nothing imported: no participant's data passed the checks (nothing written):" +
                     problems_text(checked.problems));
  if (opt.strict && !checked.problems.empty())
    throw InputError("--strict: " + std::to_string(checked.problems.size()) +
                     " input problem(s), nothing written:" + problems_text(checked.problems));
  for (const Output& o : outputs) {
    ++result.participants;
    if (o.complete) ++result.complete;
    const fs::path csv = fs::path(opt.out_dir) / (o.id + ".csv");
    result.csv_paths.push_back(csv.string());
    if (o.already_there) ++result.already_imported;
  }
  if (opt.dry_run) return result;
  fs::create_directories(opt.out_dir);
  for (const Output& o : outputs) {
    if (o.already_there) continue;
    write_file_atomically((fs::path(opt.out_dir) / (o.id + ".csv")).string(), o.csv_text);
    write_file_atomically((fs::path(opt.out_dir) / (o.id + ".json")).string(), o.json_text);
  }
  return result;
}

}  // namespace crowdlab::study
