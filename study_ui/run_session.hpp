#pragma once
// run_session: the study session engine. No I/O of its own beyond the response log and metadata;
// the participant side is a Presenter (window, scripted replay or simulated observer).
//
// Files, per participant P in out_dir:
//   P.csv   tidy responses, one row per answer (response_log.hpp for the durability rules):
//           participant,session,block,trial,stimulus,<factor columns>,question,response,reverse_coded,
//           rt_ms,timestamp,onset_utc,inter_trial_ms,frames_shown,frames_dropped,
//           frame_interval_mean_ms,frame_interval_p99_ms,frame_interval_max_ms,practice,simulated
//           session: 1 for the first run, +1 for each --resume; trial: 1-based index in this
//           participant's order; response: raw (1..k, or 1 = yes / 0 = no); reverse_coded: (k+1) - raw
//           for reverse-keyed items; rt_ms: stimulus onset to answer; timestamp: ISO 8601 UTC;
//           onset_utc: the trial's stimulus onset (ISO 8601 UTC); inter_trial_ms: inter-trial screen
//           shown -> onset (the real, measured gap); frames_*: video frames handed to the window and
//           skipped as late; frame_interval_*: between consecutive frames handed over (mean, p99,
//           max); all empty for headless presenters;
//           practice: 1 for practice trials (never analysed); simulated: 1 when a simulated observer
//           answered (--simulate, simulate-study), 0 for a person (window, --responses, import-web).
//   P.json  session metadata: spec name/hash/seed, crowdlab version, participant seed, trial count,
//           manifest sha256, consent {given, utc, session} when the spec asks for it, and one entry
//           per run (start, end, status, screen, dropped frames). Status: running, complete, aborted
//           (Esc), declined (consent refused), interrupted (killed: found "running" by a resume).
// Order of events: validate ids -> build trials -> verify every stimulus file -> refuse a used id
// unless resume -> instructions, consent -> trials (practice intro, block intros, breaks every
// protocol.break_every test trials) -> finished screen. Every trial's rows are on disk (fsync'd)
// before the next trial starts.
#include <string>

#include "framework/core/stimulus_manifest.hpp"
#include "framework/spec/experiment_spec.hpp"
#include "study_ui/participant_id.hpp"
#include "study_ui/presenter.hpp"

namespace crowdlab::study {

struct SessionOptions {
  std::string participant;  ///< [A-Za-z0-9][A-Za-z0-9_-]{0,63}
  std::string stimuli_dir;  ///< folder of manifest.csv (stimulus paths are relative to it)
  std::string out_dir;      ///< created when absent
  bool resume = false;      ///< continue a session that was interrupted
  std::string presenter_name =
      "window";              ///< recorded in the metadata ("window", "scripted", "simulated:...")
  bool verify_files = true;  ///< check existence + sha256 of every stimulus before starting
  bool durable = true;       ///< fsync every trial; false only for regenerable synthetic data
  bool simulated = false;    ///< a simulated observer answers: the rows' `simulated` column is 1
};

struct SessionResult {
  std::string csv_path;
  std::string json_path;
  int trials_total = 0;
  int trials_already_done = 0;  ///< completed before this run (resume)
  int trials_done_now = 0;
  bool complete = false;
  bool aborted = false;   ///< the participant quit (Esc confirmed): resume with --resume
  bool declined = false;  ///< the participant declined consent: no trial shown, status "declined"
  long frames_dropped = 0;
  long frames_shown = 0;
};

/// Refuses (InputError) a used id without `resume`, `resume` of an id with no session in out_dir (a
/// typo would otherwise start a new one), and a new id equal to a used one but for case.
void check_session_exists_as_asked(const std::string& out_dir, const std::string& participant, bool resume);

/// The response CSV header for a manifest's factor columns.
std::vector<std::string> response_header(const std::vector<std::string>& factor_names);

/// The tidy rows of one answered trial (one per question, columns as response_header), as written to
/// P.csv; shared with import-web so that web data land in exactly the native format.
std::vector<std::vector<std::string>> response_rows(const std::string& participant, int session,
                                                    const Trial& trial,
                                                    const std::vector<std::string>& factor_names,
                                                    const std::vector<StudyQuestion>& questions,
                                                    const std::vector<Answer>& answers,
                                                    bool simulated = false, const TrialTiming& timing = {});

/// Every check a session makes before it shows anything or writes a file: the id, the questions,
/// the trial list, the stimuli (existence and sha256, unless !options.verify_files), the id's use in
/// out_dir (check_session_exists_as_asked), and a resumed session's spec hash and log header. Throws
/// InputError. `crowdlab study` calls it before it opens the window; run_session calls it too.
void check_session_inputs(const ExperimentSpec& spec, const StimulusManifest& manifest,
                          const SessionOptions& options);

SessionResult run_session(const ExperimentSpec& spec, const StimulusManifest& manifest,
                          const SessionOptions& options, Presenter& presenter);

}  // namespace crowdlab::study
