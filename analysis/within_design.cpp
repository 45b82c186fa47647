#include "analysis/within_design.hpp"

#include <cmath>
#include <cstdint>
#include <map>
#include <set>

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

struct Row {
  size_t subject;
  std::vector<size_t> levels;
  double value;
};

size_t cell_of(const std::vector<WithinFactor>& factors, const std::vector<size_t>& levels) {
  size_t cell = 0;
  for (size_t f = 0; f < factors.size(); ++f) cell = cell * factors[f].levels.size() + levels[f];
  return cell;
}

// Refuses a design past `limits` before its subjects x cells matrix is allocated (issue 21: a CSV whose
// levels were all unique ran for minutes).
void check_design_size(const std::string& source, const std::vector<WithinFactor>& factors,
                       const DesignLimits& limits) {
  for (const auto& f : factors)
    if (f.levels.size() > limits.max_levels)
      throw InputError(
          SourceLocation{source, 0, 0, f.name},
          "factor has " + std::to_string(f.levels.size()) + " levels, more than the limit of " +
              std::to_string(limits.max_levels) +
              " (--max-levels); is it a within-subject factor, not an id or a continuous value?");
  double cells = 1;  // in double: the product of many level counts may overflow size_t
  std::string product;
  for (const auto& f : factors) {
    cells *= static_cast<double>(f.levels.size());
    product += (product.empty() ? "" : " x ") + f.name + " " + std::to_string(f.levels.size());
  }
  if (cells > static_cast<double>(limits.max_cells))
    throw InputError(source + ": the design has " + product + " = " + std::to_string(std::llround(cells)) +
                     " cells, more than the limit of " + std::to_string(limits.max_cells) + " (--max-cells)");
}

// Names the first subject that lacks a cell, from the rows alone (memory bounded by the file's rows).
void check_every_subject_has_every_cell(const std::string& source, const WithinDesign& design,
                                        const std::vector<Row>& rows, size_t cells) {
  std::set<std::pair<size_t, size_t>> seen;
  for (const auto& row : rows) seen.emplace(row.subject, cell_of(design.factors, row.levels));
  if (seen.size() == design.subjects.size() * cells) return;
  for (size_t i = 0; i < design.subjects.size(); ++i)
    for (size_t c = 0; c < cells; ++c)
      if (!seen.count({i, c}))
        throw InputError(source + ": unbalanced design: subject '" + design.subjects[i] +
                         "' has no rows for cell (" + design.cell_label(c) + ")");
}
}  // namespace

namespace {
void check_factor_names(const std::string& source, const std::vector<std::string>& within,
                        const std::vector<std::string>& between) {
  std::vector<std::string> all = within;
  all.insert(all.end(), between.begin(), between.end());
  for (size_t f = 0; f < all.size(); ++f)
    for (size_t g = 0; g < f; ++g)
      if (all[f] == all[g])
        throw InputError(SourceLocation{source, 0, 0, f < within.size() ? "--within" : "--between"},
                         "factor '" + all[f] + "' is named twice");
}

// Each subject's level of every between factor, from its first row; a later row naming another level
// is an error at that row.
void read_between_levels(const CsvTable& table, const std::vector<std::string>& between, size_t subject_col,
                         WithinDesign& design, const std::map<std::string, size_t>& subject_map) {
  design.between.resize(between.size());
  std::vector<std::map<std::string, size_t>> level_maps(between.size());
  design.subject_groups.assign(design.subjects.size(), std::vector<size_t>(between.size(), SIZE_MAX));
  for (size_t f = 0; f < between.size(); ++f) {
    design.between[f].name = between[f];
    const size_t col = table.column(between[f]);
    for (size_t r = 0; r < table.rows.size(); ++r) {
      const auto& v = table.cell(r, col);
      const SourceLocation where{table.source, table.line_numbers[r], 0, between[f]};
      if (v.empty()) throw InputError(where, "empty factor level");
      const size_t level = level_index(design.between[f].levels, level_maps[f], v);
      const size_t s = subject_map.at(table.cell(r, subject_col));
      size_t& known = design.subject_groups[s][f];
      if (known == SIZE_MAX) known = level;
      if (known != level)
        throw InputError(where, "subject '" + design.subjects[s] + "' has rows in two levels of the " +
                                    "between-subject factor ('" + design.between[f].levels[known] +
                                    "' and '" + v + "'); is it a within-subject factor?");
    }
    if (design.between[f].levels.size() < 2)
      throw InputError(table.source + ": factor '" + between[f] + "' has fewer than 2 levels");
  }
}
}  // namespace

WithinDesign build_within_design(const CsvTable& table, const std::string& dv, const std::string& subject,
                                 const std::vector<std::string>& within, const DesignLimits& limits,
                                 const std::vector<std::string>& between) {
  if (within.empty() && between.empty()) throw InputError(table.source + ": no factor given");
  const size_t dv_col = table.column(dv);
  const size_t subject_col = table.column(subject);
  std::vector<size_t> factor_cols;
  check_factor_names(table.source, within, between);
  for (const auto& b : between)
    if (b == subject || b == dv)
      throw InputError(table.source + ": factor '" + b + "' is also the subject/dv");
  for (const auto& w : within) {
    if (w == subject || w == dv)
      throw InputError(table.source + ": factor '" + w + "' is also the subject/dv");
    factor_cols.push_back(table.column(w));
  }
  WithinDesign design;
  design.source = table.source;
  design.dv = dv;
  design.factors.resize(within.size());
  std::vector<std::map<std::string, size_t>> level_maps(within.size());
  std::map<std::string, size_t> subject_map;
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
  check_design_size(table.source, design.factors, limits);
  read_between_levels(table, between, subject_col, design, subject_map);
  check_design_size(table.source, design.between, limits);
  size_t cells = 1;
  for (const auto& f : design.factors) cells *= f.levels.size();
  check_every_subject_has_every_cell(table.source, design, rows, cells);
  const auto n = static_cast<Eigen::Index>(design.subjects.size());
  Eigen::MatrixXd sums = Eigen::MatrixXd::Zero(n, static_cast<Eigen::Index>(cells));
  Eigen::MatrixXi counts = Eigen::MatrixXi::Zero(n, static_cast<Eigen::Index>(cells));
  for (const auto& row : rows) {
    const auto cell = static_cast<Eigen::Index>(cell_of(design.factors, row.levels));
    sums(static_cast<Eigen::Index>(row.subject), cell) += row.value;
    counts(static_cast<Eigen::Index>(row.subject), cell) += 1;
  }
  design.cell_means = sums.array() / counts.cast<double>().array();
  return design;
}

}  // namespace crowdlab::analysis
