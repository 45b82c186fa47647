#pragma once
// A study's answers, read from its response CSVs (real sessions or simulated ones): tidy rows with
// columns participant, block, trial, stimulus_id (or stimulus), one column per spec factor, question,
// response, reversed (the reverse-coded value: (k+1) - response for reverse-keyed items, else the
// response), rt_ms, practice. Practice rows (practice = 1/true) are dropped.
#include <string>
#include <vector>

#include "framework/core/csv.hpp"
#include "framework/spec/experiment_spec.hpp"

namespace crowdlab::analysis {

struct StudyResponses {
  std::vector<std::string> files;  ///< the CSVs read, sorted
  /// Non-practice rows of every file, with one header: participant, stimulus, question, value,
  /// <factors...>. value = the reverse-coded answer of a scale question, or 0/1 for a yes/no question
  /// (already validated, with file:line:column errors). Line numbers point into `sources[row]`.
  CsvTable table;
  std::vector<std::string> sources;  ///< per row: its file
  std::vector<std::string> factors;  ///< spec factors present (every spec factor must be a column)
};

/// Reads every *.csv under `study_dir` (recursively, sorted by path). Throws InputError naming the file
/// and column when a required column is missing, or file:line and column for a bad value.
StudyResponses read_study_responses(const std::string& study_dir, const ExperimentSpec& spec);

/// The numeric answer of a yes/no question: 1 for "yes"/"true"/"1", 0 for "no"/"false"/"0"; anything
/// else throws InputError with the row's file:line and the column.
double yes_no_value(const CsvTable& table, size_t row, size_t col);

}  // namespace crowdlab::analysis
