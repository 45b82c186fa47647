#include "analysis/study_responses.hpp"

#include <algorithm>
#include <filesystem>

#include "framework/core/error.hpp"
#include "framework/core/printable_excerpt.hpp"

namespace crowdlab::analysis {

double yes_no_value(const CsvTable& table, size_t row, size_t col) {
  std::string v = table.cell(row, col);
  std::transform(v.begin(), v.end(), v.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (v == "1" || v == "yes" || v == "true" || v == "y") return 1.0;
  if (v == "0" || v == "no" || v == "false" || v == "n") return 0.0;
  throw InputError(SourceLocation{table.source, table.line_numbers[row], 0, table.header[col]},
                   "expected a yes/no answer (yes/no, 1/0, true/false), got '" + table.cell(row, col) + "'");
}

StudyResponses read_study_responses(const std::string& study_dir, const ExperimentSpec& spec) {
  namespace fs = std::filesystem;
  if (!fs::is_directory(study_dir)) throw InputError(study_dir + ": not a directory");
  StudyResponses out;
  for (const auto& entry : fs::recursive_directory_iterator(study_dir))
    if (entry.is_regular_file() && entry.path().extension() == ".csv")
      out.files.push_back(entry.path().string());
  std::sort(out.files.begin(), out.files.end());
  if (out.files.empty()) throw InputError(study_dir + ": no response CSV files found");
  for (const auto& f : spec.factors) out.factors.push_back(f.name);
  out.table.source = study_dir;
  out.table.header = {"participant", "stimulus", "question", "value"};
  for (const auto& f : out.factors) out.table.header.push_back(f);
  for (const auto& file : out.files) {
    const CsvTable t = read_csv(file);
    const size_t participant = t.column("participant");
    const size_t stimulus = t.has_column("stimulus_id") ? t.column("stimulus_id") : t.column("stimulus");
    const size_t question = t.column("question");
    const size_t response = t.column("response");
    // The session logger writes the reverse-coded value in `reverse_coded`. Files without it (e.g.
    // exported from other tools) are reverse-coded here from the spec's question flags, never read raw.
    const bool has_reverse_coded = t.has_column("reverse_coded");
    const size_t reverse_coded = has_reverse_coded ? t.column("reverse_coded") : response;
    const bool has_practice = t.has_column("practice");
    const size_t practice = has_practice ? t.column("practice") : 0;
    std::vector<size_t> factor_cols;
    for (const auto& f : out.factors) factor_cols.push_back(t.column(f));
    for (size_t r = 0; r < t.rows.size(); ++r) {
      if (has_practice) {
        const auto& p = t.cell(r, practice);
        if (p == "1" || p == "true" || p == "True" || p == "TRUE") continue;
      }
      const auto& qid = t.cell(r, question);
      const auto q = std::find_if(spec.protocol.questions.begin(), spec.protocol.questions.end(),
                                  [&](const auto& item) { return item.id == qid; });
      if (q == spec.protocol.questions.end())
        throw InputError(SourceLocation{file, t.line_numbers[r], 0, "question"},
                         "question '" + qid + "' is not in the spec's protocol.questions");
      const int points = q->points > 0 ? q->points : spec.protocol.scale_points;
      double value = 0.0;
      if (q->kind == "yesno")
        value = yes_no_value(t, r, response);
      else if (has_reverse_coded)
        value = t.number(r, reverse_coded);
      else
        value = q->reverse ? points + 1 - t.number(r, response) : t.number(r, response);
      // An answer off the question's scale is refused where its file and row are known: 1.7e308 answers
      // overflowed a composite's mean and were reported against "responses of Q_CR" (issue 33).
      if (q->kind != "yesno" && !(value >= 1.0 && value <= points)) {
        const size_t col = has_reverse_coded ? reverse_coded : response;
        throw InputError(SourceLocation{file, t.line_numbers[r], static_cast<int>(col) + 1,
                                        "column '" + t.header[col] + "'"},
                         "question '" + qid + "': " + quote_value(t.cell(r, col)) + " is off its 1-" +
                             std::to_string(points) + " scale");
      }
      std::vector<std::string> row = {t.cell(r, participant), t.cell(r, stimulus), qid, csv_number(value)};
      for (size_t c : factor_cols) row.push_back(t.cell(r, c));
      out.table.rows.push_back(std::move(row));
      out.table.line_numbers.push_back(t.line_numbers[r]);
      out.sources.push_back(file);
    }
  }
  if (out.table.rows.empty()) throw InputError(study_dir + ": no non-practice responses");
  return out;
}

}  // namespace crowdlab::analysis
