#pragma once
// The `method` factor of a condition: which animation it shows. "baseline" is the animation stage's
// output; "ours" is the same crowd after the collision correction (seed 000 §3.4). Conditions without a
// `method` factor show the baseline. Parsed once here; stages compare the enum, never the text.
#include <cstddef>
#include <string>

#include "framework/spec/experiment_spec.hpp"

namespace crowdlab {

enum class CrowdMethod { baseline, corrected };
inline constexpr std::size_t kCrowdMethodCount = 2;

/// The method a condition shows ("ours" -> corrected; absent or any other level -> baseline).
CrowdMethod crowd_method(const Condition& condition);
/// The level text and file stem of a method: "baseline" or "ours".
const char* crowd_method_name(CrowdMethod method);
inline std::size_t index_of(CrowdMethod method) {
  return static_cast<std::size_t>(method);
}

}  // namespace crowdlab
