#pragma once
// A model the data cannot support (issue 32): its information matrix is singular or not positive
// definite (a separated factor cell, an empty cell, a parameter at a boundary that the others depend
// on), an estimate or standard error is not finite, or the optimiser did not converge.
// It is an InputError: the CLI's own model commands (`analyze clmm`, `lmm`, `psychometric`, `anova`)
// exit 2 with the reason, since the user must change the model or the data. `analyze report` writes
// "Not fitted: <why>" for that model, in report.md and in the model's JSON, and writes the rest.
#include <string>

#include "framework/core/error.hpp"

namespace crowdlab::analysis {

class ModelNotFitted : public InputError {
 public:
  using InputError::InputError;
};

/// Throws ModelNotFitted("<what>: <value> is not finite") unless `value` is finite.
void require_finite_estimate(double value, const std::string& what);

}  // namespace crowdlab::analysis
