#pragma once
// SimulatedRows: keeps simulated observers' answers out of a real analysis by accident.
// Response logs carry a `simulated` column (1 = a simulated observer answered, 0 = a person; see
// study_ui/run_session.hpp); a table without the column counts as real. `crowdlab analyze` adds every
// table it reads and refuses a mix of both unless the user asks for it (--allow-simulated-mix).
#include <string>

#include "framework/core/csv.hpp"

namespace crowdlab::analysis {

class SimulatedRows {
 public:
  /// Counts the real and simulated rows of `table` (its `simulated` column, else all real).
  void add(const CsvTable& table);
  /// Throws InputError naming a real and a simulated row when both were added and !allow_mix.
  void check(bool allow_mix) const;

 private:
  long real_ = 0, simulated_ = 0;
  std::string first_real_, first_simulated_;  ///< "file:line" of the first row of each kind
};

}  // namespace crowdlab::analysis
