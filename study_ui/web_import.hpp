#pragma once
// import_web: a web study's results (crowdlab export-web) as the per-participant tidy CSVs of native
// sessions (P.csv with run_session.hpp's columns, plus P.json metadata), so `crowdlab analyze report`
// reads online and lab data alike.
//
// Inputs (files, or folders searched recursively for *.json, *.jsonl, *.txt, *.csv), any mix of:
//   - the participant's download / a localStorage dump: {"format": "crowdlab-web-data", "records": [...]}
//   - JATOS result data (appendResultData): one record per line, {"format": "crowdlab-web-data",
//     "trial": ..., ...} (JSON lines; JATOS's exported data.txt files)
//   - jsPsych's own JSON data (jsPsych.data.get().json()): an array of trials, the records under
//     "crowdlab_record".
//   - jsPsych's CSV data (jsPsych.data.get().csv(), *.csv): RFC 4180, a header row of data keys, the
//     records as JSON text in the column "crowdlab_record" (empty on the other screens' rows). The
//     line of a CSV record is the file line of its row.
// Consent: the page's consent record ({"kind": "consent", "consent": {"given", "utc", "session"}}, in
// the JATOS data, the download's "consent_record" or jsPsych's data) goes into P.json as the native
// session's "consent"; a declined participant gets status "declined" and a P.csv with the header only.
// Timing: the record's "video" fills the native timing columns (onset_utc, inter_trial_ms,
// frames_shown = frames presented, frames_dropped, frame_interval_* from the presented frames' display
// times through frame_interval_stats).
// Checks, each a problem naming the file, line and key: the record's spec_hash is the spec's, its
// participant and order_of follow the id rule (participant_id.hpp), its stimulus sha256 is the
// manifest's, its trial number, stimulus, block and practice flag are those of the order that crowdlab
// computes for `order_of` (build_trial_list), its answers are one valid answer per question in order.
// A (participant, trial) seen twice is merged when both records are identical and refused otherwise;
// an existing P.csv in the output is left alone when identical and refused otherwise; an id that
// differs only in case from another in the results or from a file in the output is refused (as
// `crowdlab study` refuses it). A problem refuses its participant only (a file that cannot be read:
// that file only); every other participant is imported.
// Untrusted files: result files (a participant's browser wrote them) are read through
// framework/io/untrusted_json.hpp (at most 32 levels deep and max_file_bytes large), and FIFOs and
// devices are refused before they are opened; an import never replaces a file in the output folder
// (a P.json without its P.csv, or either not a regular file, is refused for that participant).
#include <cstdint>
#include <string>
#include <vector>

#include "framework/core/stimulus_manifest.hpp"
#include "framework/spec/experiment_spec.hpp"

namespace crowdlab::study {

struct WebImportOptions {
  std::string out_dir;
  std::string stimuli_dir;  ///< folder of manifest.csv (for manifest_sha256 in the metadata)
  std::uintmax_t max_file_bytes = 256u << 20;  ///< larger result files are refused (--max-file-mb)
  bool strict = false;                         ///< refuse everything when any input has a problem
  bool dry_run = false;  ///< check everything, write nothing (the CLI's check before it locks --out)
};

struct WebImportResult {
  int files = 0;
  int records = 0;
  int duplicates_merged = 0;
  int participants = 0;
  int complete = 0;          ///< participants with every trial answered
  int already_imported = 0;  ///< identical P.csv already in the output
  int declined = 0;          ///< participants who declined consent (status "declined")
  std::vector<std::string> csv_paths;
  std::vector<std::string> problems;  ///< inputs not imported: "file:line: key: why", one each
};

/// `inputs`: result files or folders. Imports every participant whose data pass the checks and lists
/// the others in `problems`. Throws InputError, writing nothing, when no participant passes, with
/// `strict` when any input has a problem, or when an input path does not exist.
WebImportResult import_web(const ExperimentSpec& spec, const StimulusManifest& manifest,
                           const std::vector<std::string>& inputs, const WebImportOptions& options);

}  // namespace crowdlab::study
