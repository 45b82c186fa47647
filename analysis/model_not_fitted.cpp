#include "analysis/model_not_fitted.hpp"

#include <cmath>
#include <cstdio>

namespace crowdlab::analysis {

void require_finite_estimate(double value, const std::string& what) {
  if (std::isfinite(value)) return;
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", value);
  throw ModelNotFitted(what + " is " + buf + ", not a finite number");
}

}  // namespace crowdlab::analysis
