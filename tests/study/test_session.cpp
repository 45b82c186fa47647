// Session engine end to end with headless presenters: data safety (fsync'd rows, torn-write
// recovery, resume without duplicates or gaps), used-id refusal, stimulus verification.
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "framework/core/csv.hpp"
#include "framework/core/error.hpp"
#include "study_ui/response_log.hpp"
#include "study_ui/run_session.hpp"
#include "study_ui/scripted_presenter.hpp"
#include "study_ui/simulate_study.hpp"
#include "study_ui/simulated_presenter.hpp"
#include "tests/study/study_fixture.hpp"
#include "tests/support/test_paths.hpp"

// This file's names, in a namespace of its own: the test executables are unity builds (issue 31).
namespace test_session {

using namespace crowdlab;
using namespace crowdlab::study;
namespace fs = std::filesystem;

namespace {

using crowdlab::test::slurp;

/// A script answering every (stimulus, question): raw = 1 + (hash of both) mod k.
fs::path write_script(const fs::path& dir, const StimulusManifest& m, const std::vector<StudyQuestion>& qs) {
  const fs::path path = dir / "script.csv";
  std::ofstream out(path);
  out << "stimulus,question,response,rt_ms\n";
  int n = 0;
  for (const auto& e : m.entries)
    for (const auto& q : qs) {
      const int raw = q.kind == QuestionKind::yesno ? (n % 2) : 1 + n % q.points;
      out << e.id << "," << q.id << ","
          << (q.kind == QuestionKind::yesno ? (raw ? "yes" : "no") : std::to_string(raw)) << ","
          << 500 + 10 * n << "\n";
      ++n;
    }
  return path;
}

/// Rows keyed by (trial, question) with the columns that must not change across a resume.
std::map<std::pair<int, std::string>, std::string> answer_map(const CsvTable& t) {
  std::map<std::pair<int, std::string>, std::string> out;
  for (size_t r = 0; r < t.rows.size(); ++r) {
    const auto key = std::make_pair(std::stoi(t.cell(r, t.column("trial"))), t.cell(r, t.column("question")));
    const std::string value = t.cell(r, t.column("stimulus")) + "|" + t.cell(r, t.column("response")) + "|" +
                              t.cell(r, t.column("reverse_coded")) + "|" + t.cell(r, t.column("rt_ms"));
    REQUIRE(out.emplace(key, value).second);  // no duplicates
  }
  return out;
}

}  // namespace

TEST_CASE("scripted Likert session writes one fsync'd tidy row per answer", "[study]") {
  const auto dir = test::scratch_dir("study-scripted");
  const auto m = test::make_stimuli(dir / "stimuli",
                                    {{"density", {"2.22", "6.66"}}, {"method", {"baseline", "ours"}}}, 2);
  ExperimentSpec spec = test::likert_spec();
  spec.protocol.break_every = 2;
  const auto qs = resolve_questions(spec.protocol);
  ScriptedPresenter presenter(write_script(dir, m, qs).string(), 0);
  presenter.check(m, qs);
  SessionOptions opt{"P07", (dir / "stimuli").string(), (dir / "out").string(), false, "scripted", true};
  const SessionResult r = run_session(spec, m, opt, presenter);
  CHECK(r.complete);
  CHECK(r.trials_total == 6);
  const CsvTable t = read_csv(r.csv_path);
  CHECK(t.header == response_header({"density", "method"}));
  REQUIRE(t.rows.size() == 6 * 6);
  int practice_rows = 0;
  for (size_t i = 0; i < t.rows.size(); ++i) {
    const std::string q = t.cell(i, t.column("question"));
    const int raw = std::stoi(t.cell(i, t.column("response")));
    const int rev = std::stoi(t.cell(i, t.column("reverse_coded")));
    const bool reverse = q == "Q2" || q == "Q4" || q == "Q6";
    CHECK(rev == (reverse ? 7 - raw : raw));
    CHECK(t.cell(i, t.column("participant")) == "P07");
    CHECK(t.cell(i, t.column("session")) == "1");
    CHECK(t.cell(i, t.column("timestamp")).size() == 24);
    CHECK(t.cell(i, t.column("timestamp")).back() == 'Z');
    practice_rows += t.cell(i, t.column("practice")) == "1";
  }
  CHECK(practice_rows == 2 * 6);
  CHECK(t.cell(0, t.column("practice")) == "1");  // practice first
  const auto meta = nlohmann::json::parse(slurp(r.json_path));
  CHECK(meta["spec_hash"] == "hash-likert");
  CHECK(meta["status"] == "complete");
  CHECK(meta["runs"].size() == 1);
  CHECK(meta.contains("crowdlab_version"));
  CHECK(meta["participant_seed"] == participant_seed(spec.seed, "P07"));

  // A used participant id is refused without --resume, and resuming a complete session adds nothing.
  CHECK_THROWS_AS(run_session(spec, m, opt, presenter), InputError);
  opt.resume = true;
  const SessionResult again = run_session(spec, m, opt, presenter);
  CHECK(again.trials_done_now == 0);
  CHECK(read_csv(r.csv_path).rows.size() == 36);
}

TEST_CASE(
    "a torn write (mid-row, at and around row ends) is repaired on resume: no duplicate, no missing row",
    "[study]") {
  const auto dir = test::scratch_dir("study-torn");
  const auto m =
      test::make_stimuli(dir / "stimuli", {{"shoulder", {"0", "1", "2"}}, {"distance", {"0.2", "0.5"}}}, 1);
  const ExperimentSpec spec = test::afc_spec();
  const auto qs = resolve_questions(spec.protocol);
  const fs::path script = write_script(dir, m, qs);
  SessionOptions opt{"P01", (dir / "stimuli").string(), (dir / "ref").string(), false, "scripted", true};
  ScriptedPresenter presenter(script.string(), 0);
  const SessionResult ref = run_session(spec, m, opt, presenter);
  const std::string full = slurp(ref.csv_path);
  const auto expected = answer_map(read_csv(ref.csv_path));
  REQUIRE(expected.size() == 7 * 2);
  // Any byte offset is a possible SIGKILL point. The log's recovery at each offset keeps exactly
  // the complete trials before it (checked against the reference file) ...
  const auto header = response_header(m.factor_names);
  const size_t header_end = full.find('\n') + 1;
  std::vector<size_t> trial_ends;  // byte offset after each complete trial (2 rows per trial)
  for (size_t pos = header_end, rows = 0; pos < full.size(); pos = full.find('\n', pos) + 1)
    if (++rows % 2 == 0) trial_ends.push_back(full.find('\n', pos) + 1);
  const fs::path cut_csv = dir / "cut.csv";
  // Offsets: around every row end (-1, 0, +1) and in the middle of every row (each reopen fsyncs,
  // which is slow on CI disks, so not literally every byte).
  std::set<size_t> cuts;
  for (size_t pos = header_end; pos < full.size();) {
    const size_t end = full.find('\n', pos) + 1;
    for (size_t c : {(pos + end) / 2, end - 1, end, end + 1})
      if (c <= full.size()) cuts.insert(c);
    pos = end;
  }
  for (size_t cut : cuts) {
    {
      std::ofstream f(cut_csv, std::ios::binary | std::ios::trunc);
      f << full.substr(0, cut);
    }
    const fs::path recovered_path = cut_csv.string() + ".recovered";
    fs::remove(recovered_path);
    RecoveredLog rec;
    { ResponseLog log = ResponseLog::reopen(cut_csv.string(), header, "trial", "session", 2, rec); }
    // A trial whose last row lacks only its newline is complete: kept, the newline restored.
    size_t kept = header_end, complete = 0;
    for (size_t e : trial_ends)
      if (e <= cut + 1) kept = e, ++complete;
    INFO("cut at byte " << cut);
    CHECK(rec.completed_trials.size() == complete);
    CHECK(fs::file_size(cut_csv) == kept);
    CHECK(slurp(cut_csv) == full.substr(0, kept));
    // Every byte cut off was first copied beside the log.
    if (cut > kept)
      CHECK(slurp(recovered_path) == full.substr(kept, cut - kept));
    else
      CHECK_FALSE(fs::exists(recovered_path));
  }
  // ... and a resumed session from a few of them (mid-row, row end, mid-trial) completes the file
  // with no duplicate and no missing row.
  opt.verify_files = false;  // verified above
  for (size_t cut : {header_end + 5, trial_ends[1], trial_ends[2] + 3, full.size() - 1}) {
    const fs::path out = dir / "cut";
    fs::remove_all(out);
    fs::create_directories(out);
    {
      std::ofstream f(out / "P01.csv", std::ios::binary);
      f << full.substr(0, cut);
    }
    opt.out_dir = out.string();
    opt.resume = true;
    const SessionResult r = run_session(spec, m, opt, presenter);
    CHECK(r.complete);
    const CsvTable t = read_csv(r.csv_path);
    CHECK(answer_map(t) == expected);
    CHECK(slurp(r.csv_path).back() == '\n');
  }
}

TEST_CASE("the response log refuses a foreign header and an incomplete middle trial", "[study]") {
  const auto dir = test::scratch_dir("study-log");
  const std::vector<std::string> header = {"participant", "session", "trial", "question"};
  const std::string path = (dir / "log.csv").string();
  {
    ResponseLog log = ResponseLog::create(path, header);
    log.append_trial({{"P", "1", "1", "a"}, {"P", "1", "1", "b"}});
    log.append_trial({{"P", "1", "2", "a"}, {"P", "1", "2", "b"}});
  }
  CHECK_THROWS_AS(ResponseLog::create(path, header), InputError);
  RecoveredLog rec;
  CHECK_THROWS_AS(
      ResponseLog::reopen(path, {"x", "session", "trial", "question"}, "trial", "session", 2, rec),
      InputError);
  {
    ResponseLog log = ResponseLog::reopen(path, header, "trial", "session", 2, rec);
    CHECK(rec.completed_trials == std::set<int>{1, 2});
    CHECK(rec.dropped_bytes == 0);
    log.append_trial({{"P", "2", "3", "a"}});  // a trial cut after its first row ...
  }
  {
    ResponseLog log = ResponseLog::reopen(path, header, "trial", "session", 2, rec);
    CHECK(rec.completed_trials == std::set<int>{1, 2});  // ... is dropped
    CHECK(rec.dropped_rows == 1);
    CHECK(rec.max_session == 1);
  }
  std::ofstream(path, std::ios::app) << "P,2,3,a\nP,2,3,b";  // complete but for the last newline
  {
    ResponseLog log = ResponseLog::reopen(path, header, "trial", "session", 2, rec);
    CHECK(rec.completed_trials == std::set<int>{1, 2, 3});
    CHECK(rec.dropped_bytes == 0);
    CHECK(rec.max_session == 2);
  }
  CHECK(slurp(path).ends_with("P,2,3,b\n"));
  CHECK(slurp(path + ".recovered") == "P,2,3,a\n");  // the first cut (trial 3's first row), kept aside
  std::ofstream(path, std::ios::app) << "P,1,4,a\nP,1,5,a\nP,1,5,b\n";  // trial 4 incomplete mid-file
  CHECK_THROWS_AS(ResponseLog::reopen(path, header, "trial", "session", 2, rec), InputError);
}

TEST_CASE("missing or corrupted stimuli stop the session before it starts", "[study]") {
  const auto dir = test::scratch_dir("study-verify");
  const auto m = test::make_stimuli(dir / "stimuli", {{"method", {"baseline", "ours"}}});
  const ExperimentSpec spec = test::likert_spec();
  SimulatedPresenter presenter(ObserverModel{}, 1);
  SessionOptions opt{"P02", (dir / "stimuli").string(), (dir / "out").string(), false, "simulated", true};
  {  // flip one byte of one clip
    std::fstream f(dir / "stimuli" / m.entries[0].file, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(100);
    f.put('\x7f');
  }
  CHECK_THROWS_AS(run_session(spec, m, opt, presenter), InputError);
  CHECK_FALSE(fs::exists(dir / "out" / "P02.csv"));
  fs::remove(dir / "stimuli" / m.entries[1].file);
  try {
    run_session(spec, m, opt, presenter);
    FAIL("expected InputError");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("missing") != std::string::npos);
  }
  CHECK_FALSE(fs::exists(dir / "out" / "P02.csv"));
}

TEST_CASE("simulated study: same format as real sessions, reproducible, merged file", "[study]") {
  const auto dir = test::scratch_dir("study-sim");
  const auto m =
      test::make_stimuli(dir / "stimuli", {{"method", {"baseline", "ours"}}, {"viewpoint", {"V1", "V3"}}}, 1);
  const ExperimentSpec spec = test::likert_spec();
  SimulateStudyOptions opt;
  opt.observers = 5;
  opt.seed = 3;
  opt.stimuli_dir = (dir / "stimuli").string();
  opt.out_dir = (dir / "a").string();
  const std::string merged = simulate_study(spec, m, ObserverModel{}, opt);
  const CsvTable t = read_csv(merged);
  CHECK(t.header == response_header({"method", "viewpoint"}));
  CHECK(t.rows.size() == 5u * 5u * 6u);
  for (int i = 0; i < 5; ++i) {
    CHECK(fs::exists(dir / "a" / (simulated_participant_id(i) + ".csv")));
    CHECK(fs::exists(dir / "a" / (simulated_participant_id(i) + ".json")));
  }
  opt.out_dir = (dir / "b").string();
  const CsvTable t2 = read_csv(simulate_study(spec, m, ObserverModel{}, opt));
  REQUIRE(t2.rows.size() == t.rows.size());
  for (size_t r = 0; r < t.rows.size(); ++r)
    CHECK(t.cell(r, t.column("response")) == t2.cell(r, t2.column("response")));
  opt.out_dir = (dir / "a").string();
  CHECK_THROWS_AS(simulate_study(spec, m, ObserverModel{}, opt), InputError);  // never overwrite
}

namespace {
/// Records the screens shown and answers every question with its lowest value.
class RecordingPresenter final : public Presenter {
 public:
  std::vector<ScreenKind> screens;
  std::vector<int> trial_indices;
  std::vector<std::string> headers;
  std::vector<std::pair<std::string, std::string>> clips;  ///< per trial: its clip, the one to prefetch
  ScreenReply consent_reply = ScreenReply::proceed;
  ScreenInfo screen() const override { return {800, 600, "recording"}; }
  ScreenReply show_screen(const PlanScreen& s) override {
    screens.push_back(s.kind);
    return s.kind == ScreenKind::consent ? consent_reply : ScreenReply::proceed;
  }
  TrialOutcome run_trial(const TrialRequest& r) override {
    trial_indices.push_back(r.trial->index);
    headers.push_back(r.header);
    clips.emplace_back(r.video_path, r.next_video_path);
    TrialOutcome out;
    for (const auto& q : *r.questions)
      out.answers.push_back({q.id, q.min_response(), 100.0, iso8601_utc_now()});
    return out;
  }
};
}  // namespace

TEST_CASE("screens: instructions, consent, practice and block intros, a break every N test trials",
          "[study]") {
  const auto dir = test::scratch_dir("study-screens");
  auto m =
      test::make_stimuli(dir / "stimuli", {{"method", {"baseline", "ours"}}, {"viewpoint", {"V1", "V3"}}}, 1);
  m.entries.back().factors["method"] = "";  // a practice trial of no block: shown before all blocks
  ExperimentSpec spec = test::likert_spec();
  spec.protocol.instructions = "Watch and answer.";
  spec.protocol.consent = "Do you agree?";
  spec.protocol.break_every = 2;
  spec.protocol.block_by = "method";
  RecordingPresenter declines;
  declines.consent_reply = ScreenReply::decline;
  SessionOptions opt{"P05", (dir / "stimuli").string(), (dir / "out").string(), false, "recording", true};
  const SessionResult refused = run_session(spec, m, opt, declines);
  CHECK(refused.declined);
  CHECK_FALSE(refused.aborted);  // declining is not Esc
  CHECK(declines.trial_indices.empty());
  CHECK(read_csv(refused.csv_path).rows.empty());
  const auto refused_meta = nlohmann::json::parse(slurp(refused.json_path));
  CHECK(refused_meta["status"] == "declined");
  CHECK(refused_meta["runs"].back()["status"] == "declined");
  CHECK(refused_meta["consent"]["given"] == false);
  CHECK(refused_meta["consent"]["utc"].get<std::string>().size() == 24);  // ISO 8601 with ms

  RecordingPresenter quits;  // Esc at the consent screen: aborted, not declined
  quits.consent_reply = ScreenReply::abort;
  opt.participant = "P04";
  const SessionResult quit = run_session(spec, m, opt, quits);
  CHECK(quit.aborted);
  CHECK_FALSE(quit.declined);
  CHECK(nlohmann::json::parse(slurp(quit.json_path))["status"] == "aborted");

  RecordingPresenter p;
  opt.participant = "P06";
  const SessionResult r = run_session(spec, m, opt, p);
  CHECK(r.complete);
  const auto meta = nlohmann::json::parse(slurp(r.json_path));
  CHECK(meta["consent"]["given"] == true);
  CHECK(meta["status"] == "complete");
  using K = ScreenKind;
  // practice (1 global trial), block 1 (2 trials), break after 2 test trials, block 2 (2 trials), end.
  const std::vector<K> expected = {K::instructions, K::consent,     K::practice_intro, K::block_intro,
                                   K::break_screen, K::block_intro, K::finished};
  CHECK(p.screens == expected);
  CHECK(p.trial_indices == std::vector<int>{1, 2, 3, 4, 5});
  // "Trial k of N" counts test trials only; the practice trial is counted apart.
  CHECK(p.headers == std::vector<std::string>{"Practice trial 1 of 1", "Trial 1 of 4", "Trial 2 of 4",
                                              "Trial 3 of 4", "Trial 4 of 4"});
}

TEST_CASE("a response log whose trial rows appear twice names the trial, not '0 rows'", "[study]") {
  // Was "trial 2 has 0 rows, expected 2" when trial 2's rows were there twice (issue 33).
  const auto dir = test::scratch_dir("study-log-twice");
  const std::vector<std::string> header = {"participant", "session", "trial", "question"};
  const std::string path = (dir / "log.csv").string();
  auto message_of_reopen = [&] {
    RecoveredLog rec;
    try {
      ResponseLog::reopen(path, header, "trial", "session", 2, rec);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  const std::string head = "participant,session,trial,question\nP,1,1,a\nP,1,1,b\n";
  const std::string trial2 = "P,1,2,a\nP,1,2,b\n";
  std::ofstream(path, std::ios::trunc) << head << trial2 << trial2;  // one block of 4 rows
  CHECK_THAT(message_of_reopen(),
             Catch::Contains("log.csv:") && Catch::Contains("trial 2 has 4 rows, expected 2"));
  std::ofstream(path, std::ios::trunc) << head << trial2 << "P,1,3,a\nP,1,3,b\n" << trial2;  // copied later
  CHECK_THAT(message_of_reopen(), Catch::Contains("log.csv:8:") &&
                                      Catch::Contains("trial 2 appears again (its rows start at line 4)"));
}

TEST_CASE("each trial names the next shown trial's clip, so the window prefetches it while answers are given",
          "[study]") {
  // Finding 12 of issue 29: the window decoded each clip whole before its onset (9-22 s between 2AFC
  // trials). It now opens the next clip while the participant answers; the engine must name that clip,
  // across parts and breaks, and name none after the last trial.
  const auto dir = test::scratch_dir("study-prefetch");
  auto m =
      test::make_stimuli(dir / "stimuli", {{"method", {"baseline", "ours"}}, {"viewpoint", {"V1", "V3"}}}, 1);
  ExperimentSpec spec = test::likert_spec();
  spec.protocol.block_by = "method";
  spec.protocol.break_every = 2;
  auto check_chain = [](const RecordingPresenter& p) {
    REQUIRE_FALSE(p.clips.empty());
    for (size_t i = 0; i + 1 < p.clips.size(); ++i) {
      CAPTURE(i);
      CHECK_FALSE(p.clips[i].first.empty());
      CHECK(p.clips[i].second == p.clips[i + 1].first);
    }
    CHECK(p.clips.back().second.empty());
  };
  RecordingPresenter all;
  SessionOptions opt{"P03", (dir / "stimuli").string(), (dir / "out").string(), false, "recording", true};
  REQUIRE(run_session(spec, m, opt, all).complete);
  REQUIRE(all.clips.size() == 5);
  check_chain(all);
  std::set<std::string> distinct;
  for (const auto& c : all.clips) distinct.insert(c.first);
  CHECK(distinct.size() == 5);  // the chain is of different clips, not one clip named twice
}

}  // namespace test_session
