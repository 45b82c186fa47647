#include "analysis/model_matrix.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <set>

#include "framework/core/error.hpp"

namespace crowdlab::analysis {
namespace {
bool parses_as_number(const std::string& s, double& value) {
  if (s.empty()) return false;
  char* end = nullptr;
  value = std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size();
}

// One variable's columns within a term: (values per row for each column, column name suffixes).
struct Coding {
  std::vector<std::vector<double>> columns;
  std::vector<std::string> names;
};

Coding code_variable(const std::string& name, const ModelVariable& v, bool contrasts, size_t rows) {
  Coding c;
  if (v.numeric) {
    c.columns.push_back(v.values);
    c.names.push_back(name);
    return c;
  }
  for (size_t l = contrasts ? 1 : 0; l < v.levels.size(); ++l) {
    std::vector<double> col(rows);
    for (size_t r = 0; r < rows; ++r) col[r] = v.codes[r] == l ? 1.0 : 0.0;
    c.columns.push_back(std::move(col));
    c.names.push_back(name + v.levels[l]);
  }
  return c;
}

bool has_term(const std::vector<ModelTerm>& terms, bool intercept, const std::set<std::string>& wanted) {
  if (wanted.empty()) return intercept;
  return std::any_of(terms.begin(), terms.end(),
                     [&](const ModelTerm& t) { return std::set<std::string>(t.begin(), t.end()) == wanted; });
}
/// The number of columns model_matrix makes, from the level counts (nothing built).
double column_count(const std::vector<ModelTerm>& terms, bool intercept,
                    const std::map<std::string, ModelVariable>& variables) {
  double count = intercept ? 1.0 : 0.0;
  for (const auto& term : terms) {
    double product = 1.0;
    for (const auto& var : term) {
      const ModelVariable& v = variables.at(var);
      if (v.numeric) continue;
      std::set<std::string> without(term.begin(), term.end());
      without.erase(var);
      const bool contrasts = has_term(terms, intercept, without);
      product *= static_cast<double>(v.levels.size()) - (contrasts ? 1.0 : 0.0);
    }
    count += product;
  }
  return count;
}
}  // namespace

void require_columns(const CsvTable& table, const std::vector<std::string>& names, const std::string& what) {
  std::vector<std::string> missing;
  for (const auto& name : names)
    if (!table.has_column(name)) missing.push_back(name);
  if (missing.empty()) return;
  const auto join = [](const std::vector<std::string>& list) {
    std::string out;
    for (const auto& s : list) out += (out.empty() ? "'" : ", '") + s + "'";
    return out;
  };
  throw InputError(SourceLocation{table.source, 1, 0, ""}, what + " names " + std::to_string(missing.size()) +
                                                               " column" + (missing.size() == 1 ? "" : "s") +
                                                               " the file lacks: " + join(missing) +
                                                               " (its columns: " + join(table.header) + ")");
}

std::map<std::string, ModelVariable> read_model_variables(const CsvTable& table,
                                                          const std::vector<std::string>& names,
                                                          const std::set<std::string>& categorical) {
  std::map<std::string, ModelVariable> out;
  for (const auto& name : names) {
    if (out.count(name)) continue;
    const size_t col = table.column(name);
    ModelVariable v;
    double value = 0;
    for (size_t r = 0; r < table.rows.size(); ++r) {
      const auto& cell = table.cell(r, col);
      if (cell.empty())
        throw InputError(SourceLocation{table.source, table.line_numbers[r], 0, name}, "empty cell");
      if (!parses_as_number(cell, value)) v.numeric = false;
    }
    const bool numeric_cells = v.numeric;
    v.numeric = v.numeric && !categorical.count(name);
    if (v.numeric) {
      for (size_t r = 0; r < table.rows.size(); ++r) {
        parses_as_number(table.cell(r, col), value);
        if (!std::isfinite(value))
          throw InputError(SourceLocation{table.source, table.line_numbers[r], 0, name},
                           "value is not finite: '" + table.cell(r, col) + "'");
        v.values.push_back(value);
      }
    } else {
      std::set<std::string> levels;
      for (size_t r = 0; r < table.rows.size(); ++r) levels.insert(table.cell(r, col));
      v.levels.assign(levels.begin(), levels.end());
      if (numeric_cells)
        std::stable_sort(v.levels.begin(), v.levels.end(), [](const std::string& a, const std::string& b) {
          double x = 0, y = 0;
          parses_as_number(a, x);
          parses_as_number(b, y);
          return x < y;
        });
      std::map<std::string, size_t> code_of;
      for (size_t l = 0; l < v.levels.size(); ++l) code_of.emplace(v.levels[l], l);
      for (size_t r = 0; r < table.rows.size(); ++r) v.codes.push_back(code_of.at(table.cell(r, col)));
    }
    out.emplace(name, std::move(v));
  }
  return out;
}

std::vector<size_t> grouping_codes(const CsvTable& table, const std::string& column,
                                   std::vector<std::string>& levels) {
  const size_t col = table.column(column);
  std::map<std::string, size_t> index;
  std::vector<size_t> codes;
  levels.clear();
  for (size_t r = 0; r < table.rows.size(); ++r) {
    const auto& cell = table.cell(r, col);
    if (cell.empty())
      throw InputError(SourceLocation{table.source, table.line_numbers[r], 0, column}, "empty cell");
    const auto [it, added] = index.emplace(cell, index.size());
    if (added) levels.push_back(cell);
    codes.push_back(it->second);
  }
  return codes;
}

ModelMatrix model_matrix(const std::vector<ModelTerm>& terms, bool intercept,
                         const std::map<std::string, ModelVariable>& variables, size_t rows) {
  // Interactions of many-level factors multiply their columns: refused from the count, before the
  // rows x columns matrix is allocated (issue 32).
  const double planned = column_count(terms, intercept, variables);
  if (planned > static_cast<double>(kMaxModelColumns))
    throw InputError("the model's terms make " + std::to_string(static_cast<long long>(planned)) +
                     " design-matrix columns (levels multiplied over each interaction), more than the limit "
                     "of " +
                     std::to_string(kMaxModelColumns) + "; drop interactions or factors with many levels");
  std::vector<std::vector<double>> columns;
  ModelMatrix m;
  if (intercept) {
    columns.emplace_back(rows, 1.0);
    m.names.push_back("(Intercept)");
  }
  for (const auto& term : terms) {
    Coding acc{{std::vector<double>(rows, 1.0)}, {""}};
    for (const auto& var : term) {
      std::set<std::string> without(term.begin(), term.end());
      without.erase(var);
      const Coding c = code_variable(var, variables.at(var), has_term(terms, intercept, without), rows);
      Coding next;
      for (size_t j = 0; j < c.columns.size(); ++j)
        for (size_t i = 0; i < acc.columns.size(); ++i) {
          std::vector<double> col(rows);
          for (size_t r = 0; r < rows; ++r) col[r] = acc.columns[i][r] * c.columns[j][r];
          next.columns.push_back(std::move(col));
          next.names.push_back(acc.names[i].empty() ? c.names[j] : acc.names[i] + ":" + c.names[j]);
        }
      acc = std::move(next);
    }
    for (size_t i = 0; i < acc.columns.size(); ++i) {
      columns.push_back(std::move(acc.columns[i]));
      m.names.push_back(acc.names[i]);
    }
  }
  m.x.resize(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(columns.size()));
  for (size_t j = 0; j < columns.size(); ++j)
    for (size_t r = 0; r < rows; ++r)
      m.x(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(j)) = columns[j][r];
  return m;
}

}  // namespace crowdlab::analysis
