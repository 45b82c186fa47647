#pragma once
// R's model matrix for the terms of a formula (Chambers & Hastie 1992, Statistical Models in S, ch. 2;
// R's model.matrix): a numeric column enters as itself; a categorical one (any cell that is not a
// number) as treatment contrasts (R's default contr.treatment): levels sorted (byte order, R's C
// locale), the first is the reference, a column per other level named variable + level
// (`methodours`). A factor in a term is coded by contrasts when the term without it is in the model
// (the intercept counts as the empty term), else by one indicator per level, as R does. Columns of an
// interaction are products, the first variable varying fastest, named with ':' (`dens_c:methodours`).
#include <Eigen/Core>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "analysis/lmm_formula.hpp"
#include "framework/core/csv.hpp"

namespace crowdlab::analysis {

struct ModelVariable {
  bool numeric = true;
  std::vector<double> values;       ///< numeric: per row
  std::vector<std::string> levels;  ///< categorical: sorted
  std::vector<size_t> codes;        ///< categorical: level index per row
};

/// Refuses, in one message naming every one of them, the `names` that are not columns of `table` (with
/// the columns it has): checked before a formula is expanded or any matrix is sized.
void require_columns(const CsvTable& table, const std::vector<std::string>& names, const std::string& what);

/// Reads the named columns. Throws InputError (file:line, column) for an empty cell or a non-finite
/// number (NaN, inf): rows are never dropped silently. A column named in `categorical` is a factor
/// even when every cell is a number (R's factor(x)); its levels are then sorted numerically, as
/// factor() sorts a numeric vector.
std::map<std::string, ModelVariable> read_model_variables(const CsvTable& table,
                                                          const std::vector<std::string>& names,
                                                          const std::set<std::string>& categorical = {});

/// A grouping factor (the `g` of a random term `(... | g)`): each row's level index, levels numbered in
/// order of first appearance (their names in `levels`). Throws InputError (file:line, column) for an
/// empty cell.
std::vector<size_t> grouping_codes(const CsvTable& table, const std::string& column,
                                   std::vector<std::string>& levels);

struct ModelMatrix {
  Eigen::MatrixXd x;
  std::vector<std::string> names;  ///< R's column names, "(Intercept)" first when present
};

/// Most columns a model matrix may have (fixed effects of a study model number in the tens).
inline constexpr std::size_t kMaxModelColumns = 2000;

/// Throws InputError, before allocating, when the terms make more than kMaxModelColumns columns.
ModelMatrix model_matrix(const std::vector<ModelTerm>& terms, bool intercept,
                         const std::map<std::string, ModelVariable>& variables, size_t rows);

}  // namespace crowdlab::analysis
