#include "analysis/within_design.hpp"

#include <cmath>
#include <map>

#include "framework/core/error.hpp"

namespace crowdlab::analysis {

std::vector<size_t> WithinDesign::cell_levels(size_t cell) const {
  std::vector<size_t> idx(factors.size());
  for (size_t f = factors.size(); f-- > 0;) {
    idx[f] = cell % factors[f].levels.size();
    cell /= factors[f].levels.size();
  }
  return idx;
}

std::string WithinDesign::cell_label(size_t cell) const {
  const auto idx = cell_levels(cell);
  std::string s;
  for (size_t f = 0; f < factors.size(); ++f) {
    if (f) s += ", ";
    s += factors[f].name + "=" + factors[f].levels[idx[f]];
  }
  return s;
}

namespace {
size_t level_index(std::vector<std::string>& levels, std::map<std::string, size_t>& index,
                   const std::string& value) {
  auto [it, inserted] = index.emplace(value, levels.size());
  if (inserted) levels.push_back(value);
  return it->second;
}
}  // namespace

WithinDesign build_within_design(const CsvTable& table, const std::string& dv, const std::string& subject,
                                 const std::vector<std::string>& within) {
  if (within.empty()) throw InputError(table.source + ": no within-subject factor given");
  const size_t dv_col = table.column(dv);
  const size_t subject_col = table.column(subject);
  std::vector<size_t> factor_cols;
  for (size_t f = 0; f < within.size(); ++f)
    for (size_t g = 0; g < f; ++g)
      if (within[f] == within[g])
        throw InputError(SourceLocation{table.source, 0, 0, "--within"},
                         "factor '" + within[f] + "' is named twice");
  for (const auto& w : within) {
    if (w == subject || w == dv)
      throw InputError(table.source + ": factor '" + w + "' is also the subject/dv");
    factor_cols.push_back(table.column(w));
  }
  WithinDesign design;
  design.factors.resize(within.size());
  std::vector<std::map<std::string, size_t>> level_maps(within.size());
  std::map<std::string, size_t> subject_map;
  struct Row {
    size_t subject;
    std::vector<size_t> levels;
    double value;
  };
  std::vector<Row> rows;
  rows.reserve(table.rows.size());
  for (size_t r = 0; r < table.rows.size(); ++r) {
    Row row;
    row.value = table.number(r, dv_col);
    if (!std::isfinite(row.value))
      throw InputError(SourceLocation{table.source, table.line_numbers[r], 0, dv},
                       "value is not finite: '" + table.cell(r, dv_col) + "'");
    const auto& s = table.cell(r, subject_col);
    if (s.empty())
      throw InputError(SourceLocation{table.source, table.line_numbers[r], 0, subject}, "empty subject");
    row.subject = level_index(design.subjects, subject_map, s);
    for (size_t f = 0; f < within.size(); ++f) {
      const auto& v = table.cell(r, factor_cols[f]);
      if (v.empty())
        throw InputError(SourceLocation{table.source, table.line_numbers[r], 0, within[f]},
                         "empty factor level");
      row.levels.push_back(level_index(design.factors[f].levels, level_maps[f], v));
    }
    rows.push_back(std::move(row));
  }
  for (size_t f = 0; f < within.size(); ++f) {
    design.factors[f].name = within[f];
    if (design.factors[f].levels.size() < 2)
      throw InputError(table.source + ": factor '" + within[f] + "' has fewer than 2 levels");
  }
  if (design.subjects.size() < 2) throw InputError(table.source + ": fewer than 2 subjects");
  size_t cells = 1;
  for (const auto& f : design.factors) cells *= f.levels.size();
  const auto n = static_cast<Eigen::Index>(design.subjects.size());
  Eigen::MatrixXd sums = Eigen::MatrixXd::Zero(n, static_cast<Eigen::Index>(cells));
  Eigen::MatrixXi counts = Eigen::MatrixXi::Zero(n, static_cast<Eigen::Index>(cells));
  for (const auto& row : rows) {
    size_t cell = 0;
    for (size_t f = 0; f < within.size(); ++f) cell = cell * design.factors[f].levels.size() + row.levels[f];
    sums(static_cast<Eigen::Index>(row.subject), static_cast<Eigen::Index>(cell)) += row.value;
    counts(static_cast<Eigen::Index>(row.subject), static_cast<Eigen::Index>(cell)) += 1;
  }
  design.cell_means.resize(n, static_cast<Eigen::Index>(cells));
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index c = 0; c < static_cast<Eigen::Index>(cells); ++c) {
      if (counts(i, c) == 0)
        throw InputError(table.source + ": unbalanced design: subject '" +
                         design.subjects[static_cast<size_t>(i)] + "' has no rows for cell (" +
                         design.cell_label(static_cast<size_t>(c)) + ")");
      design.cell_means(i, c) = sums(i, c) / counts(i, c);
    }
  return design;
}

}  // namespace crowdlab::analysis
