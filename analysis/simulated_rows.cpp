#include "analysis/simulated_rows.hpp"

#include "framework/core/error.hpp"

namespace crowdlab::analysis {

void SimulatedRows::add(const CsvTable& table) {
  const bool has = table.has_column("simulated");
  const size_t col = has ? table.column("simulated") : 0;
  for (size_t r = 0; r < table.rows.size(); ++r) {
    const std::string& v = has ? table.cell(r, col) : std::string("0");
    if (v != "0" && v != "1")
      throw InputError(SourceLocation{table.source, table.line_numbers[r], 0, "simulated"},
                       "expected 0 (a person) or 1 (a simulated observer), got '" + v + "'");
    const std::string where = table.source + ":" + std::to_string(table.line_numbers[r]);
    if (v == "1" && simulated_++ == 0) first_simulated_ = where;
    if (v == "0" && real_++ == 0) first_real_ = where;
  }
}

void SimulatedRows::check(bool allow_mix) const {
  if (allow_mix || real_ == 0 || simulated_ == 0) return;
  throw InputError(SourceLocation{"", 0, 0, "simulated"},
                   "the data mix " + std::to_string(real_) + " real row(s) (first at " + first_real_ +
                       ") and " + std::to_string(simulated_) + " simulated row(s) (first at " +
                       first_simulated_ + "); analyse them apart, or pass --allow-simulated-mix");
}

}  // namespace crowdlab::analysis
