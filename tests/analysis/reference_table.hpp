#pragma once
// Reads the committed R reference tables in tests/data/analysis/ (see scripts/make_reference_stats.R).
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "framework/core/csv.hpp"
#include "tests/support/test_paths.hpp"

namespace crowdlab::test {

inline std::string analysis_data(const std::string& name) {
  return (source_dir() / "tests" / "data" / "analysis" / name).string();
}

/// Numeric cell, NaN when empty (R's NA).
inline double ref_number(const CsvTable& t, size_t row, const std::string& col) {
  const auto& cell = t.cell(row, t.column(col));
  if (cell.empty()) return std::numeric_limits<double>::quiet_NaN();
  return t.number(row, t.column(col));
}

inline bool close_rel(double a, double b, double rel) {
  return std::abs(a - b) <= rel * std::max(std::abs(a), std::abs(b)) + 1e-300;
}

/// An optional statistic against an R cell: absent where R has NA, else equal to 1e-6 relative.
inline bool optional_matches(const std::optional<double>& got, double want) {
  if (std::isnan(want)) return !got.has_value();
  return got.has_value() && close_rel(*got, want, 1e-6);
}

}  // namespace crowdlab::test
