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
// Checks, each an InputError naming the file, line and key (exit code 2): the record's spec_hash is the
// spec's, its stimulus sha256 is the manifest's, its trial number, stimulus, block and practice flag are
// those of the order that crowdlab computes for `order_of` (build_trial_list), its answers are one valid
// answer per question in order. A (participant, trial) seen twice is merged when both records are
// identical and refused otherwise; an existing P.csv in the output is left alone when identical and
// refused otherwise, and a P.json without its P.csv (another session's) is refused: an import never
// replaces a file in the output folder. Result files are untrusted (a participant's browser wrote them):
// they are read through framework/io/untrusted_json.hpp (at most 32 levels deep and
// max_file_bytes large), and FIFOs and devices are refused before they are opened.
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
};

struct WebImportResult {
  int files = 0;
  int records = 0;
  int duplicates_merged = 0;
  int participants = 0;
  int complete = 0;          ///< participants with every trial answered
  int already_imported = 0;  ///< identical P.csv already in the output
  std::vector<std::string> csv_paths;
};

/// `inputs`: result files or folders. Throws InputError on bad input (nothing is written then).
WebImportResult import_web(const ExperimentSpec& spec, const StimulusManifest& manifest,
                           const std::vector<std::string>& inputs, const WebImportOptions& options);

}  // namespace crowdlab::study
