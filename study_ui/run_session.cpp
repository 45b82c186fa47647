#include "study_ui/run_session.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>

#include "crowdlab_version.hpp"
#include "framework/core/csv.hpp"
#include "framework/core/error.hpp"
#include "framework/core/file_kind.hpp"
#include "framework/core/sha256.hpp"
#include "framework/io/untrusted_json.hpp"
#include "study_ui/response_log.hpp"
#include "study_ui/session_plan.hpp"
#include "study_ui/verify_stimuli.hpp"

namespace crowdlab::study {
namespace fs = std::filesystem;
namespace {

/// A duration in ms to 0.1 ms; negative (not measured) as an empty cell.
std::string ms_text(double ms) {
  return ms < 0 ? "" : csv_number(std::round(ms * 10.0) / 10.0);
}

const std::vector<std::string> kFixedColumns = {"participant",
                                                "session",
                                                "block",
                                                "trial",
                                                "stimulus",
                                                "question",
                                                "response",
                                                "reverse_coded",
                                                "rt_ms",
                                                "timestamp",
                                                "onset_utc",
                                                "inter_trial_ms",
                                                "frames_shown",
                                                "frames_dropped",
                                                "frame_interval_mean_ms",
                                                "frame_interval_p99_ms",
                                                "frame_interval_max_ms",
                                                "practice",
                                                "simulated"};

/// P.json of an earlier session: untrusted (it may have been edited or replaced), so read with the
/// limits of untrusted_json.hpp, and its shape checked where the session reads it.
nlohmann::json read_metadata(const std::string& path) {
  if (!fs::exists(fs::symlink_status(path))) return nlohmann::json::object();
  require_writable_destination(path);  // rewritten by this session: never through a link
  JsonLimits limits;
  limits.max_bytes = 16u << 20;
  const nlohmann::json meta = read_untrusted_json(path, "session metadata", limits);
  if (!meta.is_object())
    throw InputError(SourceLocation{path, 0, 0, ""}, "session metadata must be a JSON object");
  if (meta.contains("runs") && !meta["runs"].is_array())
    throw InputError(SourceLocation{path, 0, 0, "runs"},
                     "expected a list of runs, got " + meta["runs"].dump());
  if (meta.contains("runs"))
    for (const auto& run : meta["runs"])
      if (!run.is_object())
        throw InputError(SourceLocation{path, 0, 0, "runs"}, "each run must be a JSON object");
  if (meta.contains("spec_hash") && !meta["spec_hash"].is_string())
    throw InputError(SourceLocation{path, 0, 0, "spec_hash"}, "expected a string");
  return meta;
}

void check_answers(const TrialOutcome& outcome, const std::vector<StudyQuestion>& questions,
                   const Trial& trial) {
  if (outcome.answers.size() != questions.size())
    throw RuntimeError("trial " + std::to_string(trial.index) + ": presenter returned " +
                       std::to_string(outcome.answers.size()) + " answers for " +
                       std::to_string(questions.size()) + " questions");
  for (size_t i = 0; i < questions.size(); ++i) {
    const Answer& a = outcome.answers[i];
    if (a.question_id != questions[i].id || !questions[i].valid(a.raw) || !std::isfinite(a.rt_ms) ||
        a.rt_ms < 0)
      throw RuntimeError("trial " + std::to_string(trial.index) + ": invalid answer to " + questions[i].id +
                         " (" + std::to_string(a.raw) + ")");
  }
}

}  // namespace

std::vector<std::vector<std::string>> response_rows(const std::string& participant, int session,
                                                    const Trial& trial,
                                                    const std::vector<std::string>& factor_names,
                                                    const std::vector<StudyQuestion>& questions,
                                                    const std::vector<Answer>& answers, bool simulated,
                                                    const TrialTiming& timing) {
  std::vector<std::vector<std::string>> rows;
  for (size_t i = 0; i < questions.size(); ++i) {
    const StudyQuestion& q = questions[i];
    const Answer& a = answers[i];
    std::vector<std::string> row = {participant, std::to_string(session), trial.block,
                                    std::to_string(trial.index), trial.stimulus.id};
    for (const auto& f : factor_names) {
      auto it = trial.stimulus.factors.find(f);
      row.push_back(it == trial.stimulus.factors.end() ? "" : it->second);
    }
    row.push_back(q.id);
    row.push_back(std::to_string(a.raw));
    row.push_back(std::to_string(reverse_coded(q, a.raw)));
    row.push_back(csv_number(std::round(a.rt_ms * 10.0) / 10.0));
    row.push_back(a.timestamp_utc);
    row.push_back(timing.onset_utc);
    row.push_back(ms_text(timing.inter_trial_ms));
    const bool measured = !timing.onset_utc.empty();
    row.push_back(measured ? std::to_string(timing.frames_shown) : "");
    row.push_back(measured ? std::to_string(timing.frames_dropped) : "");
    row.push_back(ms_text(timing.intervals.mean_ms));
    row.push_back(ms_text(timing.intervals.p99_ms));
    row.push_back(ms_text(timing.intervals.max_ms));
    row.push_back(trial.practice ? "1" : "0");
    row.push_back(simulated ? "1" : "0");
    rows.push_back(std::move(row));
  }
  return rows;
}

void check_session_exists_as_asked(const std::string& out_dir, const std::string& participant, bool resume) {
  const fs::path dir(out_dir);
  const bool used = fs::exists(dir / (participant + ".csv")) || fs::exists(dir / (participant + ".json"));
  if (used && !resume)
    throw InputError(SourceLocation{"", 0, 0, "--participant"},
                     "participant '" + participant + "' already has a session in " + out_dir +
                         " (use --resume to continue it, or another id)");
  if (!used && resume)
    throw InputError(SourceLocation{"", 0, 0, "--resume"},
                     "participant '" + participant + "' has no session in " + out_dir +
                         " to resume (a typo? drop --resume to start a new session)");
  if (used) return;
  if (const auto other = case_clash(out_dir, participant))
    throw InputError(SourceLocation{"", 0, 0, "--participant"},
                     "participant '" + participant + "' clashes with '" + *other + "' in " + out_dir +
                         ": ids differing only in case are one participant");
}

std::vector<std::string> response_header(const std::vector<std::string>& factor_names) {
  std::vector<std::string> header(kFixedColumns.begin(), kFixedColumns.begin() + 5);
  for (const auto& f : factor_names) {
    for (const auto& fixed : kFixedColumns)
      if (f == fixed)
        throw InputError("factor '" + f + "' clashes with the response column of the same name; rename it");
    header.push_back(f);
  }
  header.insert(header.end(), kFixedColumns.begin() + 5, kFixedColumns.end());
  return header;
}

void check_session_inputs(const ExperimentSpec& spec, const StimulusManifest& manifest,
                          const SessionOptions& opt) {
  check_participant_id(opt.participant);
  resolve_questions(spec.protocol);
  if (build_trial_list(spec.protocol, manifest, spec.seed, opt.participant).empty())
    throw InputError(SourceLocation{"", 0, 0, "--stimuli"}, "the manifest holds no trial for this spec");
  const std::string header_line = csv_line(response_header(manifest.factor_names));
  if (opt.verify_files) verify_stimuli(manifest, opt.stimuli_dir);
  check_session_exists_as_asked(opt.out_dir, opt.participant, opt.resume);
  const fs::path dir(opt.out_dir);
  const std::string json_path = (dir / (opt.participant + ".json")).string();
  const nlohmann::json meta = read_metadata(json_path);
  if (meta.contains("spec_hash") && meta["spec_hash"] != spec.source_hash)
    throw InputError(json_path + ": this participant's session used another spec (hash " +
                     meta["spec_hash"].get<std::string>() + "); refusing to mix data");
  const fs::path csv_path = dir / (opt.participant + ".csv");
  // Appended to by this session: a link (to a file outside --out) or a FIFO is refused before it is
  // opened (issue 32).
  require_writable_destination(csv_path);
  std::ifstream csv(csv_path, std::ios::binary);
  std::string first_line;
  if (csv && std::getline(csv, first_line) && first_line + "\n" != header_line)
    throw InputError(SourceLocation{csv_path.string(), 1, 0, ""},
                     "the response log's header differs from this spec and manifest (another study, or a "
                     "log of an older crowdlab version)");
}

SessionResult run_session(const ExperimentSpec& spec, const StimulusManifest& manifest,
                          const SessionOptions& opt, Presenter& presenter) {
  check_session_inputs(spec, manifest, opt);
  const std::vector<StudyQuestion> questions = resolve_questions(spec.protocol);
  const SessionPlan plan = session_plan(spec, manifest, opt.participant);
  const std::vector<Trial>& trials = plan.trials;
  const std::vector<std::string> header = response_header(manifest.factor_names);

  SessionResult result;
  result.csv_path = (fs::path(opt.out_dir) / (opt.participant + ".csv")).string();
  result.json_path = (fs::path(opt.out_dir) / (opt.participant + ".json")).string();
  result.trials_total = static_cast<int>(trials.size());
  fs::create_directories(opt.out_dir);
  nlohmann::json meta = read_metadata(result.json_path);
  RecoveredLog recovered;
  std::optional<ResponseLog> log;
  if (fs::exists(result.csv_path)) {
    log.emplace(ResponseLog::reopen(result.csv_path, header, "trial", "session",
                                    static_cast<int>(questions.size()), recovered, opt.durable));
    if (recovered.dropped_bytes > 0)
      spdlog::warn(
          "{}: cut {} byte(s) of an interrupted trial ({} complete row(s) of it; copied to {}.recovered); it "
          "will be asked again",
          result.csv_path, recovered.dropped_bytes, recovered.dropped_rows, result.csv_path);
  } else {
    log.emplace(ResponseLog::create(result.csv_path, header, opt.durable));
  }
  for (const Trial& t : trials)
    if (recovered.completed_trials.count(t.index)) ++result.trials_already_done;
  if (static_cast<int>(recovered.completed_trials.size()) != result.trials_already_done)
    throw InputError(result.csv_path + ": holds trial indices this spec and manifest do not produce");
  if (recovered.max_session == std::numeric_limits<int>::max())
    throw InputError(SourceLocation{result.csv_path, 0, 0, "session"},
                     "the log's last session is " + std::to_string(recovered.max_session) +
                         ", the largest session number; another session cannot be numbered");
  const int session = recovered.max_session + 1;

  const ScreenInfo screen = presenter.screen();
  if (!meta.contains("participant")) {
    meta["participant"] = opt.participant;
    meta["spec_name"] = spec.name;
    meta["spec_path"] = spec.source_path;
    meta["spec_hash"] = spec.source_hash;
    meta["spec_seed"] = spec.seed;
    meta["participant_seed"] = participant_seed(spec.seed, opt.participant);
    meta["crowdlab_version"] = CROWDLAB_VERSION;
    meta["protocol"] = kind_name(spec.protocol.type);
    meta["simulated"] = opt.simulated;
    meta["trials"] = trials.size();
    meta["questions"] = nlohmann::json::array();
    for (const auto& q : questions) meta["questions"].push_back({{"id", q.id}, {"reverse", q.reverse}});
    const std::string manifest_csv = (fs::path(opt.stimuli_dir) / "manifest.csv").string();
    meta["manifest_sha256"] = fs::exists(manifest_csv) ? sha256_file_hex(manifest_csv) : "";
    meta["runs"] = nlohmann::json::array();
    meta["start_utc"] = iso8601_utc_now();
  }
  for (auto& earlier : meta["runs"])
    if (earlier.value("status", "") == "running") earlier["status"] = "interrupted";  // killed or crashed
  nlohmann::json run = {
      {"session", session},
      {"start_utc", iso8601_utc_now()},
      {"end_utc", nullptr},
      {"status", "running"},
      {"presenter", opt.presenter_name},
      {"screen", {{"width", screen.width}, {"height", screen.height}, {"kind", screen.kind}}},
      {"resumed_at_trials_done", result.trials_already_done}};
  meta["runs"].push_back(run);
  meta["end_utc"] = nullptr;
  auto save_meta = [&](const std::string& status) {
    auto& r = meta["runs"].back();
    r["status"] = status;
    if (status != "running") r["end_utc"] = iso8601_utc_now();
    r["frames_shown"] = result.frames_shown;
    r["frames_dropped"] = result.frames_dropped;
    r["trials_done"] = result.trials_already_done + result.trials_done_now;
    meta["status"] = status;
    if (status == "complete") meta["end_utc"] = r["end_utc"];
    write_file_atomically(result.json_path, meta.dump(2) + "\n", opt.durable);
  };
  save_meta("running");
  spdlog::info("participant {}: session {}, {} trial(s), {} already done", opt.participant, session,
               trials.size(), result.trials_already_done);

  auto abort_session = [&] {
    result.aborted = true;
    save_meta("aborted");
    spdlog::warn("participant {}: session aborted after {} trial(s); resume with --resume", opt.participant,
                 result.trials_already_done + result.trials_done_now);
    return result;
  };
  // The plan's steps in order, resumed per skip_on_resume (session_plan.hpp): the same rule the web
  // page applies.
  const ProtocolSpec& p = spec.protocol;
  std::vector<const PlanStep*> shown;
  for (const PlanStep& step : plan.steps)
    if (!skip_on_resume(step, recovered.completed_trials)) shown.push_back(&step);
  for (size_t k = 0; k < shown.size(); ++k) {
    const PlanStep& step = *shown[k];
    if (step.kind == StepKind::screen) {
      if (step.screen.kind == ScreenKind::finished) break;  // after the session is saved complete
      const ScreenReply reply = presenter.show_screen(step.screen);
      if (reply == ScreenReply::abort) return abort_session();
      if (step.screen.kind != ScreenKind::consent) continue;
      // Given or declined, with when and in which run: part of the record a study must keep.
      const bool given = reply == ScreenReply::proceed;
      meta["consent"] = {{"given", given}, {"utc", iso8601_utc_now()}, {"session", session}};
      if (!given) {
        result.declined = true;
        save_meta("declined");
        spdlog::info("participant {}: declined to take part; no trial was shown", opt.participant);
        return result;
      }
      save_meta("running");
      continue;
    }
    const Trial& t = plan.trials[static_cast<size_t>(step.trial - 1)];
    TrialRequest req;
    req.trial = &t;
    req.video_path = stimulus_path(opt.stimuli_dir, t.stimulus);
    for (size_t n = k + 1; n < shown.size(); ++n)
      if (shown[n]->kind == StepKind::trial) {
        req.next_video_path =
            stimulus_path(opt.stimuli_dir, plan.trials[static_cast<size_t>(shown[n]->trial - 1)].stimulus);
        break;
      }
    req.questions = &questions;
    req.trial_count = static_cast<int>(trials.size());
    req.header = step.header;
    req.min_view_ms = step.min_view_ms;
    req.loop_video = p.loop_video;
    req.fps = spec.fps;
    req.inter_trial_screen = p.inter_trial_screen;
    req.inter_trial_min_ms = p.inter_trial_min_ms;
    req.video_share = p.video_share;
    TrialOutcome outcome = presenter.run_trial(req);
    result.frames_shown += outcome.timing.frames_shown;
    result.frames_dropped += outcome.timing.frames_dropped;
    if (outcome.aborted) return abort_session();
    check_answers(outcome, questions, t);
    log->append_trial(response_rows(opt.participant, session, t, manifest.factor_names, questions,
                                    outcome.answers, opt.simulated, outcome.timing));
    ++result.trials_done_now;
    if (outcome.timing.frames_dropped > 0)
      spdlog::info("trial {} ({}): {} of {} frame(s) dropped", t.index, t.stimulus.id,
                   outcome.timing.frames_dropped,
                   outcome.timing.frames_shown + outcome.timing.frames_dropped);
    save_meta("running");  // progress and dropped frames survive a kill too
  }
  result.complete = true;
  save_meta("complete");
  presenter.show_screen(plan.steps.back().screen);
  spdlog::info("participant {}: complete, responses in {}", opt.participant, result.csv_path);
  return result;
}

}  // namespace crowdlab::study
