#pragma once
// precondition(): what a deeper layer asserts instead of validating again (issue 30). The spec loader
// checks every range and key once, with file:line:column (framework/spec/load_experiment_spec.cpp), so
// that `validate` refuses everything `run` would; a stage that reads a checked value states the check as
// a precondition. A value that breaks it comes from code that built a spec without the loader: a
// programming error, thrown as std::logic_error (exit 1), never an InputError asking the user to edit the
// spec.
#include <stdexcept>
#include <string>

namespace crowdlab {

/// Throws std::logic_error naming `what` (the key and the range the loader checked) unless `holds`.
inline void precondition(bool holds, const std::string& what) {
  if (!holds) throw std::logic_error("precondition failed: " + what + " (checked by the spec loader)");
}

}  // namespace crowdlab
